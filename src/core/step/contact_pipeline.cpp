// The contact pipeline: the index set (12) at q_M through the broad phase and the collision table,
// see contact_pipeline.h.
#include "nonsmooth_sim/core/step/contact_pipeline.h"

#include <algorithm>
#include <limits>
#include <tuple>

#include "nonsmooth_sim/core/contact/contact_frame.h"
#include "nonsmooth_sim/core/contact/contact_key.h"
#include "nonsmooth_sim/core/nearly_sorted.h"

namespace nonsmooth_sim {

void ContactPipeline::Resize(const Model& model) {
  spheres_.clear();
  spheres_.reserve(model.scene.colliders.size());
  pairs_.reserve(2 * model.scene.colliders.size());
  merged_pairs_.reserve(2 * model.scene.colliders.size());
}

namespace {

// A contact with rolling components (HasRolling): dimension 6, the rolling rows of W at q_M.
// Out of line: a step without rolling does not carry its code.
[[gnu::cold, gnu::noinline]] void AddRollingRows(const Model& model, ClosedContact* contact,
                                                 StepData* data) {
  ContactState& r = contact->report;
  r.dimension = 6;
  data->any_rolling = true;
  for (int s = 0; s < 2; ++s) {
    const int body = contact->jacobian.side[s].body;
    if (body < 0) continue;
    const std::size_t b = static_cast<std::size_t>(body);
    SetRollingRows(ContactRollingRows(r.frame, data->body[b].rotation_mid), model.inertia[b],
                   &contact->rolling.side[s]);
  }
}

}  // namespace

void ContactPipeline::FindContacts(const Model& model, const std::vector<BodyState>& state,
                                   StepData* data, StepStatistics* stats) {
  const std::vector<Collider>& colliders = model.scene.colliders;
  data->closed_count = 0;
  data->any_rolling = false;
  pairs_.clear();
  // broad phase: every body collider against every static plane, the rest by sweep and prune;
  // kMoreau2 pads the bounding spheres by the persistent contacts' margin (AddPairContacts)
  const double pad = data->second_order ? kPersistentContactMargin : 0.0;
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    const Collider& c = colliders[i];
    if (c.shape.type == ShapeType::kPlane) continue;
    UpdateColliderPose(model, state, static_cast<int>(i), /*end=*/false, data);
    if (c.body == kWorld) continue;
    const Eigen::Vector3d center = data->collider_pose[i].translation();
    for (int p : model.planes) {
      const Eigen::Isometry3d& plane = colliders[static_cast<std::size_t>(p)].pose;
      // height of the centre above the plane z = 0 of the plane frame
      const double height = plane.linear().col(2).dot(center - plane.translation());
      if (height <= model.bounding_radius[i] + pad) {
        pairs_.emplace_back(std::min(static_cast<int>(i), p), std::max(static_cast<int>(i), p));
      }
    }
  }
  // in collider order, unless a plane comes between a body's colliders
  SortNearlySorted(pairs_.begin(), pairs_.end());
  if (model.needs_sweep) {
    // the spheres in the sweep order of the last step (Resize empties it)
    if (spheres_.empty()) {
      for (std::size_t i = 0; i < colliders.size(); ++i) {
        const Collider& c = colliders[i];
        if (c.shape.type == ShapeType::kPlane) continue;
        spheres_.push_back(
            BoundingSphere{Eigen::Vector3d::Zero(), 0.0, static_cast<int>(i), c.body});
      }
    }
    for (BoundingSphere& sphere : spheres_) {
      const std::size_t i = static_cast<std::size_t>(sphere.collider);
      sphere.center = data->collider_pose[i].translation();
      sphere.radius = model.bounding_radius[i] + pad;
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
  for (const auto& [first, second] : pairs_) AddPairContacts(model, state, first, second, data);
  stats->closed_contacts = static_cast<int>(data->closed_count);
  for (std::size_t i = 0; i < data->closed_count; ++i) {
    const ClosedContact& c = data->closed[i];
    stats->max_penetration = std::max(stats->max_penetration, -c.report.gap);
    // a contact not closed in the last step: found this deep, a part of a step late
    if (c.memory->closed_step != data->step - 1) {
      stats->new_contact_depth = std::max(stats->new_contact_depth, -c.report.gap);
    }
  }
}

void ContactPipeline::AddPairContacts(const Model& model, const std::vector<BodyState>& state,
                                      int first, int second, StepData* data) {
  const std::vector<Collider>& colliders = model.scene.colliders;
  ContactMemoryMap& memories = data->memory;
  const long step = data->step;
  // A is the static collider if there is one, else the first
  int a = first;
  int b = second;
  if (colliders[static_cast<std::size_t>(b)].body == kWorld) std::swap(a, b);
  const Collider& collider_a = colliders[static_cast<std::size_t>(a)];
  const Collider& collider_b = colliders[static_cast<std::size_t>(b)];
  const Eigen::Isometry3d& pose_a = data->collider_pose[static_cast<std::size_t>(a)];
  const Eigen::Isometry3d& pose_b = data->collider_pose[static_cast<std::size_t>(b)];
  ContactGeometry* geometry = geometry_.data();
  // (12): g(q_M) ≤ 0, or ≤ kContactHysteresis while the pair had a closed contact in the last
  // step (of any feature: a face that tilts past the flat tolerance hands over to its corners)
  const std::uint64_t pair_key = ContactKey(first, second, kPairFeature);
  const auto found = memories.find(pair_key);
  // a pointer: the features' try_emplace below may rehash (iterators die, references do not)
  ContactMemory* pair_memory = found != memories.end() ? &found->second : nullptr;
  const bool pair_was_closed = pair_memory != nullptr && pair_memory->closed_step == step - 1;
  const double max_gap = pair_was_closed ? kContactHysteresis : 0.0;
  // kMoreau2: a feature closed in the last step also while g(q_B) ≤ kPersistentContactGap
  const bool persistent =
      pair_was_closed && data->second_order && data->previous_time_step > 0.0;
  // points up to the hysteresis gap (the margin for persistent ones): the index set below
  // decides which close
  const int count =
      model.scene.collision_table.Collide(collider_a.shape, pose_a, collider_b.shape, pose_b,
                                          persistent ? kPersistentContactMargin
                                                     : kContactHysteresis,
                                          geometry);
  if (count <= 0) return;  // apart, or no pair function (the scene loader reports those)
  const ContactLaw law = model.PairLaw(first, second);
  // a new contact's first tangent: a plane's x axis (the ground: world x̂), else world x̂
  const Eigen::Vector3d hint = collider_a.shape.type == ShapeType::kPlane
                                   ? Eigen::Vector3d(pose_a.linear().col(0))
                                   : Eigen::Vector3d::UnitX();
  bool any_closed = false;
  for (int k = 0; k < count; ++k) {
    const ContactGeometry& g = geometry[k];
    const std::uint64_t key = ContactKey(first, second, g.feature);
    if (g.gap > max_gap) {
      if (!persistent) continue;
      const auto feature = memories.find(key);
      if (feature == memories.end() || feature->second.closed_step != step - 1 ||
          !(feature->second.gap_end <= kPersistentContactGap)) {
        continue;
      }
    }
    any_closed = true;
    auto memory = memories.end();
    if (data->closed_count == data->closed.size()) data->closed.emplace_back();
    ClosedContact& c = data->closed[data->closed_count++];
    c.key = key;
    // the (pair, feature)'s memory, created on first contact (the only allocation of a step)
    bool created = false;
    std::tie(memory, created) = memories.try_emplace(c.key);
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
    r.rolling_percussion.setZero();
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
      const BodyStep& w = data->body[static_cast<std::size_t>(side.body)];
      SetAngularRows(ContactAngularRows(r.frame, *points[s], w.position_mid, w.rotation_mid),
                     model.inertia[static_cast<std::size_t>(side.body)], &side);
      // γ^B enters c only through ε (16), and in kMoreau2's end-point law
      if (r.law.restitution == 0.0 && !data->second_order) continue;
      const BodyState& begin = state[static_cast<std::size_t>(side.body)];
      // γ^B = W(q_M)ᵀu_B
      c.gamma_begin +=
          SideVelocity(c.jacobian, side, begin.linear_velocity, begin.angular_velocity);
    }
    if (r.law.rolling_resistance > 0.0f && HasRolling(r.law)) AddRollingRows(model, &c, data);
  }
  // the pair's own memory: closed in this step
  if (any_closed) {
    if (pair_memory == nullptr) pair_memory = &memories.try_emplace(pair_key).first->second;
    pair_memory->closed_step = step;
  }
}

void ContactPipeline::RecordEndGaps(const Model& model, const std::vector<BodyState>& state,
                                    StepData* data) {
  const std::vector<Collider>& colliders = model.scene.colliders;
  std::size_t i = 0;
  while (i < data->closed_count) {
    // the contacts of one pair are consecutive in data->closed
    std::size_t j = i;
    while (j < data->closed_count && data->closed[j].key >> 16 == data->closed[i].key >> 16) ++j;
    const ContactState& first = data->closed[i].report;
    const std::size_t a = static_cast<std::size_t>(first.collider_a);
    const std::size_t b = static_cast<std::size_t>(first.collider_b);
    UpdateColliderPose(model, state, first.collider_a, /*end=*/true, data);
    UpdateColliderPose(model, state, first.collider_b, /*end=*/true, data);
    ContactGeometry* end = geometry_.data();
    const int count = model.scene.collision_table.Collide(
        colliders[a].shape, data->collider_pose[a], colliders[b].shape, data->collider_pose[b],
        kPersistentContactMargin, end);
    for (std::size_t k = i; k < j; ++k) {
      double gap = std::numeric_limits<double>::infinity();  // the feature is gone
      for (int e = 0; e < count; ++e) {
        if (end[e].feature == data->closed[k].report.feature) gap = end[e].gap;
      }
      data->closed[k].memory->gap_end = gap;
    }
    i = j;
  }
}

}  // namespace nonsmooth_sim
