// The position projection after (15) (SimulatorOptions::gap_correction; not part of the paper's
// scheme, which is velocity-level and lets a rolling contact drift into its surface by O(Δt²) per
// step). The closed contacts (12) of the step are evaluated again at q_E (same pair, same
// feature, collision.h):
//  - per body and static collider it touches, and per pair of bodies (a group), if every closed
//    contact of the group ends below -kGapCorrectionSlop, the body is translated along the
//    group's normal until the highest of them is at -kGapCorrectionSlop; a pair of bodies shares
//    the translation in inverse proportion to the masses (the pair's centre of mass stays). The
//    highest decides: a lift never opens a contact that carried the body.
//  - a body on several points of one static collider is levelled instead (LevelOnPoints): the
//    smallest rigid displacement (Δr, Δθ) in the metric of M that brings every point to ≥ -slop,
//      g_i + n_i·Δr + (r_i × n_i)·Δθ ≥ -slop,  Δr = Σ n_i λ_i / m,  Δθ = Θ_w⁻¹ Σ (r_i × n_i) λ_i,
//    λ_i ≥ 0 complementary, by projected Gauss-Seidel; a buried body is first lifted straight.
// Velocities are kept.
#ifndef NONSMOOTH_SIM_CORE_STEP_POSITION_PROJECTION_H_
#define NONSMOOTH_SIM_CORE_STEP_POSITION_PROJECTION_H_

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/core/model.h"
#include "nonsmooth_sim/core/step/step_data.h"

namespace nonsmooth_sim {

/// Penetration a closed contact may keep before gap_correction lifts its body [m]. Far below every
/// geometric scale of the scenes (Tippe-Top: contact radius R = 0.5 mm, peg radius 5 mm; block
/// and disc feet 10 mm) and far above the per-step O(Δt²) drift of a rolling contact (measured at
/// most 1.6e-9 m per step for the top rocking at Δt = 1e-3, less at smaller Δt): a body at rest
/// never sinks to it and a short rolling phase rarely does (the rocking top needs ~1.3 s), while a
/// contact that keeps rolling is then held at -kGapCorrectionSlop by lifts of the size of that
/// per-step drift (nearly every step).
inline constexpr double kGapCorrectionSlop = 1e-6;

/// Projected Gauss-Seidel sweeps of the levelling of a body on several points of one static
/// collider (SimulatorOptions::gap_correction): at most 8 points with a diagonal-dominant
/// Delassus matrix; 30 sweeps bring a 10 µm tilt to the slop within 1e-12 m (measured on a box
/// on four corners and a capsule on its two ends).
inline constexpr int kLevellingSweeps = 30;

class PositionProjection {
 public:
  /// Moves the bodies of `state` (q_E: positions and orientations, data->body[b].rotation_end its
  /// A(p_E)) out of the closed contacts data->closed[0, closed_count) as above (collider poses at
  /// q_E into data->collider_pose). stats: gap_correction (largest |Δr|) and
  /// gap_correction_energy (Σ -m g·Δr) accumulate. Returns whether a body moved.
  bool CorrectGaps(const Model& model, StepData* data, std::vector<BodyState>* state,
                   StepStatistics* stats);

 private:
  // The closed contacts of one body with one static collider, or of two bodies, at q_E.
  struct GapGroup {
    int body_a = kWorld;        // kWorld for a static A
    int body_b = 0;
    int static_collider = -1;  // A's collider if it is static
    double highest_gap = 0.0;  // g(q_E) [m]
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  };
  // levels a body on the closed contacts [first, last) of data.closed (one pair with a static
  // collider, end geometry `end`); false if fewer than two of them are found at q_E
  bool LevelOnPoints(const Model& model, const StepData& data, std::size_t first,
                     std::size_t last, const ContactGeometry* end, int count,
                     std::vector<BodyState>* state, StepStatistics* stats);

  std::vector<GapGroup> gap_groups_;
  std::array<ContactGeometry, kMaxPairContacts> geometry_;
  bool moved_ = false;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_POSITION_PROJECTION_H_
