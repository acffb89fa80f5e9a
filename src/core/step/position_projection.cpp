// The position projection after (15): gap correction by group lifts and levelling on several
// points, see position_projection.h.
#include "nonsmooth_sim/core/step/position_projection.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "nonsmooth_sim/core/nearly_sorted.h"
#include "nonsmooth_sim/core/step/contact_pipeline.h"

namespace nonsmooth_sim {

bool PositionProjection::CorrectGaps(const Model& model, StepData* data,
                                     std::vector<BodyState>* state, StepStatistics* stats) {
  moved_ = false;
  // raw arrays: the loop calls the pair functions, after which the compiler would load every
  // vector's fields again
  const ClosedContact* const closed = data->closed.data();
  const std::size_t closed_count = data->closed_count;
  const Collider* const colliders = model.scene.colliders.data();
  const Eigen::Isometry3d* const collider_pose = data->collider_pose.data();
  // One record per closed contact, evaluated again at q_E: its group (a body and the static
  // collider it touches, or a pair of bodies), its end gap and normal. Sorted by group, the
  // highest gap first: that one decides for the group (two spheres of one body on the ground are
  // one group).
  gap_groups_.clear();
  std::size_t i = 0;
  while (i < closed_count) {
    // the contacts of one pair are consecutive in closed
    std::size_t j = i;
    while (j < closed_count && closed[j].key >> 16 == closed[i].key >> 16) ++j;
    const ContactState& first = closed[i].report;
    ContactGeometry* end = geometry_.data();
    // the poses at q_E (collider_pose held q_M for the contact pipeline, which sets it anew each
    // step); a static A keeps the pose it always has
    const std::size_t a = static_cast<std::size_t>(first.collider_a);
    const std::size_t b = static_cast<std::size_t>(first.collider_b);
    UpdateColliderPose(model, *state, first.collider_a, /*end=*/true, data);
    UpdateColliderPose(model, *state, first.collider_b, /*end=*/true, data);
    const int count = model.scene.collision_table.Collide(
        colliders[a].shape, collider_pose[a], colliders[b].shape, collider_pose[b], 0.0, end);
    // a body resting on several points of one static collider (a face, corners, a capsule on
    // its side): levelled by a rotation and translation (LevelOnPoints), not only lifted
    if (first.body_a == kWorld && j - i >= 2 &&
        LevelOnPoints(model, *data, i, j, end, count, state, stats)) {
      i = j;
      continue;
    }
    for (std::size_t k = i; k < j; ++k) {
      const ContactState& r = closed[k].report;
      double gap = std::numeric_limits<double>::infinity();  // feature gone: not penetrating
      Eigen::Vector3d normal = r.frame.normal;
      for (int e = 0; e < count; ++e) {
        if (end[e].feature != r.feature) continue;
        gap = end[e].gap;
        normal = end[e].normal;
      }
      GapGroup& group = gap_groups_.emplace_back();
      group.body_a = r.body_a;
      group.body_b = r.body_b;
      group.static_collider = r.body_a < 0 ? r.collider_a : -1;
      group.highest_gap = gap;
      group.normal = normal;
    }
    i = j;
  }
  // merge the records of one group: the highest end gap decides, with its normal
  // (the records come in pair order: nearly sorted by body already)
  const auto by_group = [](const GapGroup& x, const GapGroup& y) {
    if (x.body_b != y.body_b) return x.body_b < y.body_b;
    if (x.body_a != y.body_a) return x.body_a < y.body_a;
    if (x.static_collider != y.static_collider) return x.static_collider < y.static_collider;
    return x.highest_gap > y.highest_gap;
  };
  SortNearlySorted(gap_groups_.begin(), gap_groups_.end(), by_group);
  BodyState* const s = state->data();
  const GapGroup* const groups = gap_groups_.data();
  const std::size_t group_count = gap_groups_.size();
  for (std::size_t k = 0; k < group_count; ++k) {
    const GapGroup& g = groups[k];
    if (k > 0 && g.body_b == groups[k - 1].body_b && g.body_a == groups[k - 1].body_a &&
        g.static_collider == groups[k - 1].static_collider) {
      continue;  // not the highest of its group
    }
    const double depth = -g.highest_gap;
    if (!(depth > kGapCorrectionSlop)) continue;
    // translate along the normal to the slop; a pair of bodies shares it by mass
    const double push = depth - kGapCorrectionSlop;
    const double mass_b = model.inertia[static_cast<std::size_t>(g.body_b)].mass;
    const double mass_a =
        g.body_a >= 0 ? model.inertia[static_cast<std::size_t>(g.body_a)].mass : 0.0;
    const double share_b = g.body_a >= 0 ? mass_a / (mass_a + mass_b) : 1.0;
    const Eigen::Vector3d move_b = (share_b * push) * g.normal;
    moved_ = true;
    s[static_cast<std::size_t>(g.body_b)].position += move_b;
    stats->gap_correction = std::max(stats->gap_correction, move_b.norm());
    stats->gap_correction_energy -= mass_b * model.scene.gravity.dot(move_b);
    if (g.body_a >= 0) {
      const Eigen::Vector3d move_a = -((1.0 - share_b) * push) * g.normal;
      s[static_cast<std::size_t>(g.body_a)].position += move_a;
      stats->gap_correction = std::max(stats->gap_correction, move_a.norm());
      stats->gap_correction_energy -= mass_a * model.scene.gravity.dot(move_a);
    }
  }
  return moved_;
}

bool PositionProjection::LevelOnPoints(const Model& model, const StepData& data,
                                       std::size_t first, std::size_t last,
                                       const ContactGeometry* end, int count,
                                       std::vector<BodyState>* state, StepStatistics* stats) {
  // the closed contacts [first, last) of one body B with one static collider, at q_E
  const int body = data.closed[first].report.body_b;
  BodyState& s = (*state)[static_cast<std::size_t>(body)];
  const BodyInertia& inertia = model.inertia[static_cast<std::size_t>(body)];
  const Eigen::Matrix3d& rotation = data.body[static_cast<std::size_t>(body)].rotation_end;
  const Eigen::Matrix3d inverse_inertia_world =
      rotation * inertia.inverse_inertia * rotation.transpose();
  constexpr int kMaxPoints = kMaxPairContacts;
  Eigen::Vector3d normal[kMaxPoints];
  Eigen::Vector3d moment[kMaxPoints];  // r_i × n_i
  double gap[kMaxPoints];
  double diagonal[kMaxPoints];
  int n = 0;
  double deepest = 0.0;
  for (std::size_t k = first; k < last && n < kMaxPoints; ++k) {
    for (int e = 0; e < count; ++e) {
      if (end[e].feature != data.closed[k].report.feature) continue;
      normal[n] = end[e].normal;
      moment[n] = (end[e].point_b - s.position).cross(end[e].normal);
      gap[n] = end[e].gap;
      diagonal[n] = inertia.inverse_mass + moment[n].dot(inverse_inertia_world * moment[n]);
      deepest = std::min(deepest, gap[n]);
      ++n;
    }
  }
  if (n < 2) return false;                            // one point: the lift of the group rule
  if (!(-deepest > kGapCorrectionSlop)) return true;  // within the slop: nothing to do
  // the smallest displacement (Δr, Δθ) in the metric of M that brings every point to ≥ -slop:
  //   g_i + n_i·Δr + (r_i × n_i)·Δθ ≥ -slop,  Δr = Σ n_i λ_i / m,  Δθ = Θ_w⁻¹ Σ (r_i × n_i) λ_i,
  // λ_i ≥ 0 complementary, by projected Gauss-Seidel (a few points, well conditioned)
  double lambda[kMaxPoints] = {};
  Eigen::Vector3d dr = Eigen::Vector3d::Zero();
  Eigen::Vector3d dtheta = Eigen::Vector3d::Zero();
  // A buried body, its highest point here deeper than the diameter of its collider's bounding
  // sphere (so all of it is under the surface; e.g. a die reset 10 m deep), is first lifted
  // straight along the common normal until that point is at -slop (the lift of the group rule,
  // which opens no contact), and only the rest, at most the body's size, is levelled. Without
  // it the sweeps give the lift to the points listed first (a box's upper corners, only 2h
  // shallower than its lower face) and drain their λ back to 0 in O(depth / h) sweeps:
  // kLevellingSweeps left the die 10 m deep turned by 33° (0.67 rad of Δθ), where the exact
  // solution is the straight lift. Ordinary penetrations (far shallower than a diameter: the
  // sweeps converge up to depths of ~40 h for a die) level exactly as before.
  double highest = gap[0];
  bool one_normal = true;  // a plane: every gap changes by exactly the lift
  for (int p = 1; p < n; ++p) {
    highest = std::max(highest, gap[p]);
    one_normal = one_normal && normal[p] == normal[0];
  }
  const double diameter = 2.0 * model.bounding_radius[static_cast<std::size_t>(
                                    data.closed[first].report.collider_b)];
  if (one_normal && -highest > diameter && -highest > kGapCorrectionSlop) {
    dr = (-highest - kGapCorrectionSlop) * normal[0];
  }
  for (int sweep = 0; sweep < kLevellingSweeps; ++sweep) {
    for (int p = 0; p < n; ++p) {
      const double residual =
          gap[p] + kGapCorrectionSlop + normal[p].dot(dr) + moment[p].dot(dtheta);
      const double updated = std::max(0.0, lambda[p] - residual / diagonal[p]);
      const double change = updated - lambda[p];
      lambda[p] = updated;
      dr += (change * inertia.inverse_mass) * normal[p];
      dtheta += change * (inverse_inertia_world * moment[p]);
    }
  }
  // apply: translate r_S, rotate about S by the world rotation Δθ; velocities kept
  moved_ = true;
  s.position += dr;
  const double angle = dtheta.norm();
  if (angle > 0.0) {
    s.orientation =
        (Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle)) * s.orientation).normalized();
  }
  stats->gap_correction = std::max(stats->gap_correction, dr.norm());
  stats->gap_correction_energy -= inertia.mass * model.scene.gravity.dot(dr);
  return true;
}

}  // namespace nonsmooth_sim
