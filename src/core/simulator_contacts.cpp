// Contacts of a step, see simulator.h: the index set (12) at q_M through the broad phase and the
// collision table, the islands of bodies the closed contacts link, and the gap correction at q_E.
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "nonsmooth_sim/core/contact/contact_frame.h"
#include "nonsmooth_sim/core/contact/contact_key.h"
#include "nonsmooth_sim/core/nearly_sorted.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

// The feature id of a pair's own memory (ContactKey with it: "the pair had a closed contact").
constexpr int kPairFeature = 0xffff;

// Union-find root with path halving.
int Root(std::vector<int>* parent, int b) {
  std::vector<int>& p = *parent;
  while (p[static_cast<std::size_t>(b)] != b) {
    p[static_cast<std::size_t>(b)] = p[static_cast<std::size_t>(p[static_cast<std::size_t>(b)])];
    b = p[static_cast<std::size_t>(b)];
  }
  return b;
}

}  // namespace

void Simulator::UpdateColliderPose(int collider, bool end) {
  const Collider& c = scene_.colliders[static_cast<std::size_t>(collider)];
  Eigen::Isometry3d& pose = collider_pose_[static_cast<std::size_t>(collider)];
  if (c.body == kWorld) return;  // set once in Initialize
  const BodyStep& w = body_step_[static_cast<std::size_t>(c.body)];
  const Eigen::Matrix3d& rotation = end ? w.rotation_end : w.rotation_mid;
  const Eigen::Vector3d& position =
      end ? state_[static_cast<std::size_t>(c.body)].position : w.position_mid;
  // (A, r_S) ∘ pose, written out in place: Eigen's Transform product multiplies the full 4 × 4
  // matrices (the last row stays (0, 0, 0, 1) from Initialize)
  if (collider_rotated_[static_cast<std::size_t>(collider)]) {
    pose.linear().noalias() = rotation * c.pose.linear();
  } else {
    pose.linear() = rotation;  // a sphere at an offset, a shape in the body's axes
  }
  pose.translation().noalias() = rotation * c.pose.translation();
  pose.translation() += position;
}

void Simulator::FindContacts(StepStatistics* stats) {
  closed_count_ = 0;
  pairs_.clear();
  // broad phase: every body collider against every static plane, the rest by sweep and prune
  for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
    const Collider& c = scene_.colliders[i];
    if (c.shape.type == ShapeType::kPlane) continue;
    UpdateColliderPose(static_cast<int>(i), /*end=*/false);
    if (c.body == kWorld) continue;
    const Eigen::Vector3d center = collider_pose_[i].translation();
    for (int p : planes_) {
      const Eigen::Isometry3d& plane = scene_.colliders[static_cast<std::size_t>(p)].pose;
      // height of the centre above the plane z = 0 of the plane frame
      const double height = plane.linear().col(2).dot(center - plane.translation());
      if (height <= bounding_radius_[i]) {
        pairs_.emplace_back(std::min(static_cast<int>(i), p), std::max(static_cast<int>(i), p));
      }
    }
  }
  // in collider order, unless a plane comes between a body's colliders
  SortNearlySorted(pairs_.begin(), pairs_.end());
  if (needs_sweep_) {
    // the spheres in the sweep order of the last step (BuildCaches empties it)
    if (spheres_.empty()) {
      for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
        const Collider& c = scene_.colliders[i];
        if (c.shape.type == ShapeType::kPlane) continue;
        spheres_.push_back(
            BoundingSphere{Eigen::Vector3d::Zero(), 0.0, static_cast<int>(i), c.body});
      }
    }
    for (BoundingSphere& sphere : spheres_) {
      const std::size_t i = static_cast<std::size_t>(sphere.collider);
      sphere.center = collider_pose_[i].translation();
      sphere.radius = bounding_radius_[i];
    }
    // a deterministic order: by collider pair (the contact order of the Gauss-Seidel sweep),
    // the sweep's pairs sorted apart and merged with the planes'
    const std::size_t plane_pairs = pairs_.size();
    SweepAndPrune(&spheres_, &pairs_);
    if (pairs_.size() > plane_pairs) {
      std::sort(pairs_.begin() + static_cast<std::ptrdiff_t>(plane_pairs), pairs_.end());
      merged_pairs_.resize(pairs_.size());
      std::merge(pairs_.begin(), pairs_.begin() + static_cast<std::ptrdiff_t>(plane_pairs),
                 pairs_.begin() + static_cast<std::ptrdiff_t>(plane_pairs), pairs_.end(),
                 merged_pairs_.begin());
      pairs_.swap(merged_pairs_);
    }
  }
  for (const auto& [first, second] : pairs_) AddPairContacts(first, second);
  stats->closed_contacts = static_cast<int>(closed_count_);
}

void Simulator::AddPairContacts(int first, int second) {
  // A is the static collider if there is one, else the first
  int a = first;
  int b = second;
  if (scene_.colliders[static_cast<std::size_t>(b)].body == kWorld) std::swap(a, b);
  const Collider& collider_a = scene_.colliders[static_cast<std::size_t>(a)];
  const Collider& collider_b = scene_.colliders[static_cast<std::size_t>(b)];
  const Eigen::Isometry3d& pose_a = collider_pose_[static_cast<std::size_t>(a)];
  const Eigen::Isometry3d& pose_b = collider_pose_[static_cast<std::size_t>(b)];
  ContactGeometry* geometry = geometry_.data();
  // points up to the hysteresis gap: the index set below decides which close
  const int count =
      Collide(collider_a.shape, pose_a, collider_b.shape, pose_b, kContactHysteresis, geometry);
  if (count <= 0) return;  // apart, or no pair function (the scene loader reports those)
  const ContactLaw law = PairLaw(first, second);
  // a new contact's first tangent: a plane's x axis (the ground: world x̂), else world x̂
  const Eigen::Vector3d hint = collider_a.shape.type == ShapeType::kPlane
                                   ? Eigen::Vector3d(pose_a.linear().col(0))
                                   : Eigen::Vector3d::UnitX();
  // (12): g(q_M) ≤ 0, or ≤ kContactHysteresis while the pair had a closed contact in the last
  // step (of any feature: a face that tilts past the flat tolerance hands over to its corners)
  const std::uint64_t pair_key = ContactKey(first, second, kPairFeature);
  const auto found = memory_.find(pair_key);
  // a pointer: the features' try_emplace below may rehash (iterators die, references do not)
  ContactMemory* pair_memory = found != memory_.end() ? &found->second : nullptr;
  const bool pair_was_closed =
      pair_memory != nullptr && pair_memory->closed_step == step_count_ - 1;
  const double max_gap = pair_was_closed ? kContactHysteresis : 0.0;
  bool any_closed = false;
  for (int k = 0; k < count; ++k) {
    const ContactGeometry& g = geometry[k];
    const std::uint64_t key = ContactKey(first, second, g.feature);
    if (g.gap > max_gap) continue;
    any_closed = true;
    auto memory = memory_.end();
    if (closed_count_ == closed_.size()) closed_.emplace_back();
    ClosedContact& c = closed_[closed_count_++];
    c.key = key;
    // the (pair, feature)'s memory, created on first contact (the only allocation of a step)
    bool created = false;
    std::tie(memory, created) = memory_.try_emplace(c.key);
    c.memory = &memory->second;
    const Eigen::Vector3d* previous = created ? nullptr : &c.memory->tangent1;
    ContactState& r = c.report;
    r.collider_a = a;
    r.collider_b = b;
    r.body_a = collider_a.body;
    r.body_b = collider_b.body;
    r.feature = g.feature;
    r.gap = g.gap;
    r.point = g.point_b;
    r.frame = MakeContactFrame(g.normal, previous, hint);
    r.law = law;
    // a point of a face lying flat: the spread of the face's points carries the drilling torque
    // of its uniform pressure, the point itself has no drilling component (collision.h)
    if (g.face_point) r.law.rbar = 0.0;
    r.dimension = ContactDimension(r.law);
    r.percussion.setZero();
    // W at q_M over B (+) and A (-)
    c.jacobian.linear = ContactLinearRows(r.frame);
    c.gamma_begin.setZero();
    const Eigen::Vector3d* points[2] = {&g.point_b, &g.point_a};
    const int bodies[2] = {r.body_b, r.body_a};
    for (int s = 0; s < 2; ++s) {
      ContactSide& side = c.jacobian.side[s];
      side.body = bodies[s];
      side.sign = s == 0 ? 1.0 : -1.0;
      if (side.body < 0) continue;
      const BodyStep& w = body_step_[static_cast<std::size_t>(side.body)];
      SetAngularRows(ContactAngularRows(r.frame, *points[s], w.position_mid, w.rotation_mid),
                     inertia_[static_cast<std::size_t>(side.body)], &side);
      if (r.law.restitution == 0.0) continue;  // γ^B enters c only through ε (16)
      const BodyState& state = state_[static_cast<std::size_t>(side.body)];
      // γ^B = W(q_M)ᵀu_B
      c.gamma_begin +=
          SideVelocity(c.jacobian, side, state.linear_velocity, state.angular_velocity);
    }
  }
  // the pair's own memory: closed in this step
  if (any_closed) {
    if (pair_memory == nullptr) pair_memory = &memory_.try_emplace(pair_key).first->second;
    pair_memory->closed_step = step_count_;
  }
}

void Simulator::BuildIslands(StepStatistics* stats) {
  islands_.clear();
  if (closed_count_ == 0) return;
  stats->islands = 1;
  for (std::size_t i = 0; i < closed_count_; ++i) {
    stats->max_penetration = std::max(stats->max_penetration, -closed_[i].report.gap);
  }
  // one body against the static world (a top on the ground): one island, contacts in order
  bool single = true;
  for (std::size_t i = 0; i < closed_count_; ++i) {
    single = single && closed_[i].report.body_a < 0 &&
             closed_[i].report.body_b == closed_[0].report.body_b;
  }
  if (single) {
    islands_.push_back(Island{0, static_cast<int>(closed_count_)});
    island_contacts_.resize(closed_count_);
    for (std::size_t i = 0; i < closed_count_; ++i) {
      island_contacts_[i] = static_cast<int>(i);
    }
    body_step_[static_cast<std::size_t>(closed_[0].report.body_b)].island = 0;
    island_bodies_.resize(1);
    island_bodies_[0] = closed_[0].report.body_b;
    island_body_start_.resize(2);
    island_body_start_[0] = 0;
    island_body_start_[1] = 1;
    return;
  }
  // union-find over the bodies that closed contacts link
  for (std::size_t b = 0; b < union_find_.size(); ++b) union_find_[b] = static_cast<int>(b);
  for (std::size_t i = 0; i < closed_count_; ++i) {
    const ClosedContact& c = closed_[i];
    if (c.report.body_a < 0) continue;
    const int ra = Root(&union_find_, c.report.body_a);
    const int rb = Root(&union_find_, c.report.body_b);
    if (ra != rb) union_find_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }
  // islands numbered in the order of their first contact; body_step_[root].island holds it
  for (std::size_t i = 0; i < closed_count_; ++i) {
    const int root = Root(&union_find_, closed_[i].report.body_b);
    BodyStep& w = body_step_[static_cast<std::size_t>(root)];
    if (w.island < 0) {
      w.island = static_cast<int>(islands_.size());
      islands_.push_back(Island{});
    }
    ++islands_[static_cast<std::size_t>(w.island)].contact_count;
  }
  // counting sort of the contacts by island, keeping their order within an island
  int start = 0;
  for (Island& island : islands_) {
    island.first_contact = start;
    start += island.contact_count;
    island.contact_count = 0;
  }
  island_contacts_.resize(closed_count_);
  for (std::size_t i = 0; i < closed_count_; ++i) {
    const int root = Root(&union_find_, closed_[i].report.body_b);
    Island& island =
        islands_[static_cast<std::size_t>(body_step_[static_cast<std::size_t>(root)].island)];
    island_contacts_[static_cast<std::size_t>(island.first_contact + island.contact_count++)] =
        static_cast<int>(i);
  }
  // every body of an island knows it; the bodies grouped by island
  for (std::size_t b = 0; b < body_step_.size(); ++b) {
    const int root = Root(&union_find_, static_cast<int>(b));
    body_step_[b].island = body_step_[static_cast<std::size_t>(root)].island;
  }
  island_body_start_.assign(islands_.size() + 1, 0);
  for (const BodyStep& w : body_step_) {
    if (w.island >= 0) ++island_body_start_[static_cast<std::size_t>(w.island) + 1];
  }
  for (std::size_t k = 1; k < island_body_start_.size(); ++k) {
    island_body_start_[k] += island_body_start_[k - 1];
  }
  island_bodies_.resize(static_cast<std::size_t>(island_body_start_.back()));
  std::vector<int>& next = union_find_;  // reused as the fill pointer per island
  for (std::size_t k = 0; k < islands_.size(); ++k) next[k] = island_body_start_[k];
  for (std::size_t b = 0; b < body_step_.size(); ++b) {
    const int island = body_step_[b].island;
    if (island < 0) continue;
    island_bodies_[static_cast<std::size_t>(next[static_cast<std::size_t>(island)]++)] =
        static_cast<int>(b);
  }
  stats->islands = static_cast<int>(islands_.size());
}

void Simulator::CorrectGaps(StepStatistics* stats) {
  // One record per closed contact, evaluated again at q_E: its group (a body and the static
  // collider it touches, or a pair of bodies), its end gap and normal. Sorted by group, the
  // highest gap first: that one decides for the group (two spheres of one body on the ground are
  // one group).
  gap_groups_.clear();
  std::size_t i = 0;
  while (i < closed_count_) {
    // the contacts of one pair are consecutive in closed_
    std::size_t j = i;
    while (j < closed_count_ && closed_[j].key >> 16 == closed_[i].key >> 16) ++j;
    const ContactState& first = closed_[i].report;
    ContactGeometry* end = geometry_.data();
    // A static: its pose is the one it always has
    // the poses at q_E (collider_pose_ held q_M for FindContacts, which sets it anew each step)
    const std::size_t a = static_cast<std::size_t>(first.collider_a);
    const std::size_t b = static_cast<std::size_t>(first.collider_b);
    UpdateColliderPose(first.collider_a, /*end=*/true);
    UpdateColliderPose(first.collider_b, /*end=*/true);
    const int count = Collide(scene_.colliders[a].shape, collider_pose_[a],
                              scene_.colliders[b].shape, collider_pose_[b], 0.0, end);
    // a body resting on several points of one static collider (a face, corners, a capsule on
    // its side): levelled by a rotation and translation (LevelOnPoints), not only lifted
    if (first.body_a == kWorld && j - i >= 2 && LevelOnPoints(i, j, end, count, stats)) {
      i = j;
      continue;
    }
    for (std::size_t k = i; k < j; ++k) {
      const ContactState& r = closed_[k].report;
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
  for (std::size_t k = 0; k < gap_groups_.size(); ++k) {
    const GapGroup& g = gap_groups_[k];
    if (k > 0 && g.body_b == gap_groups_[k - 1].body_b && g.body_a == gap_groups_[k - 1].body_a &&
        g.static_collider == gap_groups_[k - 1].static_collider) {
      continue;  // not the highest of its group
    }
    const double depth = -g.highest_gap;
    if (!(depth > kGapCorrectionSlop)) continue;
    // translate along the normal to the slop; a pair of bodies shares it by mass
    const double push = depth - kGapCorrectionSlop;
    const double mass_b = inertia_[static_cast<std::size_t>(g.body_b)].mass;
    const double mass_a = g.body_a >= 0 ? inertia_[static_cast<std::size_t>(g.body_a)].mass : 0.0;
    const double share_b = g.body_a >= 0 ? mass_a / (mass_a + mass_b) : 1.0;
    const Eigen::Vector3d move_b = (share_b * push) * g.normal;
    gap_moved_ = true;
    state_[static_cast<std::size_t>(g.body_b)].position += move_b;
    stats->gap_correction = std::max(stats->gap_correction, move_b.norm());
    stats->gap_correction_energy -= mass_b * scene_.gravity.dot(move_b);
    if (g.body_a >= 0) {
      const Eigen::Vector3d move_a = -((1.0 - share_b) * push) * g.normal;
      state_[static_cast<std::size_t>(g.body_a)].position += move_a;
      stats->gap_correction = std::max(stats->gap_correction, move_a.norm());
      stats->gap_correction_energy -= mass_a * scene_.gravity.dot(move_a);
    }
  }
}

bool Simulator::LevelOnPoints(std::size_t first, std::size_t last, const ContactGeometry* end,
                              int count, StepStatistics* stats) {
  // the closed contacts [first, last) of one body B with one static collider, at q_E
  const int body = closed_[first].report.body_b;
  BodyState& s = state_[static_cast<std::size_t>(body)];
  const BodyInertia& inertia = inertia_[static_cast<std::size_t>(body)];
  const Eigen::Matrix3d& rotation = body_step_[static_cast<std::size_t>(body)].rotation_end;
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
      if (end[e].feature != closed_[k].report.feature) continue;
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
  const double diameter = 2.0 * bounding_radius_[static_cast<std::size_t>(
                                    closed_[first].report.collider_b)];
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
  gap_moved_ = true;
  s.position += dr;
  const double angle = dtheta.norm();
  if (angle > 0.0) {
    s.orientation =
        (Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle)) * s.orientation).normalized();
  }
  stats->gap_correction = std::max(stats->gap_correction, dr.norm());
  stats->gap_correction_energy -= inertia.mass * scene_.gravity.dot(dr);
  return true;
}

}  // namespace nonsmooth_sim
