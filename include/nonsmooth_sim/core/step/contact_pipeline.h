// The contact pipeline of a step: the index set (12) at the midpoint q_M, eq. (12) of the paper.
//   broad phase (broad_phase.h): every body collider against every static plane, the rest by
//     sweep and prune over bounding spheres, in a deterministic order (by collider pair);
//   narrow phase: the pair function of the scene's collision table (collision_table.h) gives
//     points, normals, gaps and features; those with g(q_M) ≤ 0 (≤ kContactHysteresis for a pair
//     closed in the last step) are the closed contacts;
//   per closed contact: its memory across steps by (pair, feature) (contact_memory.h), its frame
//     with the tangent carried over (contact_frame.h), its W over one or two bodies and γ^B
//     (contact_jacobian.h).
#ifndef NONSMOOTH_SIM_CORE_STEP_CONTACT_PIPELINE_H_
#define NONSMOOTH_SIM_CORE_STEP_CONTACT_PIPELINE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/collision/broad_phase.h"
#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/core/model.h"
#include "nonsmooth_sim/core/step/step_data.h"

namespace nonsmooth_sim {

/// A contact closed in the last step stays in the index set (12) up to this positive gap [m]. A
/// body resting on a flat face or several corners sits at g = 0 up to round-off; without it the
/// contacts of such a face open for single steps at gaps of 1e-18 m and the body falls freely
/// for a step (a hop of g Δt). A contact that separates has Λ = 0 whether it is in the index set
/// or not (no adhesion; its friction bound μΛ_N is 0), so this changes nothing but the catching
/// of a body that comes back within 1 nm of where it left: far below every scale of the scenes.
/// The broad phase pads every bounding sphere by it (Model's bounding radii), so that it passes
/// such a pair to the narrow phase (a sphere's bounding sphere is the sphere itself).
inline constexpr double kContactHysteresis = 1e-9;

/// Integrator::kMoreau2 keeps a contact closed in the last step in the index set while it ended
/// that step within this gap (g(q_E) ≤ 1e-6 m), whatever g(q_M): a contact point that moves over
/// a curved surface lies above it at the midpoint q_M = q_B + Δt/2 u_B (a straight line in the
/// coordinates) by O(Δt²) (Euler's disk: ~1e-7 m at Δt = 1e-4), which would open it for a step,
/// differently for steps of Δt and Δt/2. A separating contact in the index set gets Λ_N = 0.
inline constexpr double kPersistentContactGap = 1e-6;
/// The broad phase and the pair functions look this far [m] for such contacts (kMoreau2).
inline constexpr double kPersistentContactMargin = 1e-4;
/// The feature id of a pair's own memory (ContactKey with it: "the pair had a closed contact").
inline constexpr int kPairFeature = 0xffff;

/// data->collider_pose of collider `collider` on a body at q_M (end = false: A(p_M), r_S(q_M)
/// of data->body) or q_E (end = true: A(p_E) of data->body, r_S of `state`); a static collider's
/// pose is left as it is.
[[gnu::always_inline]] inline void UpdateColliderPose(const Model& model,
                                                      const std::vector<BodyState>& state,
                                                      int collider, bool end, StepData* data) {
  const Collider& c = model.scene.colliders[static_cast<std::size_t>(collider)];
  Eigen::Isometry3d& pose = data->collider_pose[static_cast<std::size_t>(collider)];
  if (c.body == kWorld) return;  // set once by StepData::Resize
  const BodyStep& w = data->body[static_cast<std::size_t>(c.body)];
  const Eigen::Matrix3d& rotation = end ? w.rotation_end : w.rotation_mid;
  const Eigen::Vector3d& position =
      end ? state[static_cast<std::size_t>(c.body)].position : w.position_mid;
  // (A, r_S) ∘ pose, written out in place: Eigen's Transform product multiplies the full 4 × 4
  // matrices (the last row stays (0, 0, 0, 1) from StepData::Resize)
  if (model.collider_rotated[static_cast<std::size_t>(collider)]) {
    pose.linear().noalias() = rotation * c.pose.linear();
  } else {
    pose.linear() = rotation;  // a sphere at an offset, a shape in the body's axes
  }
  pose.translation().noalias() = rotation * c.pose.translation();
  pose.translation() += position;
}

class ContactPipeline {
 public:
  /// Sizes the workspace for `model` (after every change of the scene).
  void Resize(const Model& model);
  /// (12) at q_M (data->body's midpoints, `state` = q_B, u_B for γ^B): the closed contacts into
  /// data->closed[0, closed_count), ordered by collider pair and feature, each with its memory
  /// (created on first contact), frame, law, W and γ^B; the pairs' own memories record the step
  /// data->step. stats: closed_contacts and max_penetration.
  void FindContacts(const Model& model, const std::vector<BodyState>& state, StepData* data,
                    StepStatistics* stats);
  /// Integrator::kMoreau2: g(q_E) of every closed contact into its memory (gap_end), with the
  /// collider poses at q_E (`state` = q_E).
  void RecordEndGaps(const Model& model, const std::vector<BodyState>& state, StepData* data);

 private:
  void AddPairContacts(const Model& model, const std::vector<BodyState>& state, int first,
                       int second, StepData* data);

  // the colliders that are not planes in the sweep order of the last step (emptied by Resize):
  // nearly sorted for the next step's sweep
  std::vector<BoundingSphere> spheres_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<std::pair<int, int>> merged_pairs_;  // the merge of plane and sweep pairs
  // the pair function's output (a member: eight ContactGeometry are not free to construct)
  std::array<ContactGeometry, kMaxPairContacts> geometry_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_CONTACT_PIPELINE_H_
