// The model of a simulation, as MuJoCo's mjModel: the scene (with its collision table), the
// per-pair friction-set overrides, the external wrenches, and the arrays derived from the scene
// once. The step reads it and never writes it; only Simulator's setters and world changes
// (AddBodies, RemoveBodies) do, between two steps, and they call BuildCaches after changing the
// scene.
#ifndef NONSMOOTH_SIM_CORE_MODEL_H_
#define NONSMOOTH_SIM_CORE_MODEL_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/friction_law.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {

/// The external wrench of one body (Simulator::SetExternalWrench), world axes.
struct BodyWrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< [N], through S
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< [N m]
  bool set = false;                                  ///< not both zero
};

struct Model {
  Scene scene;
  /// Friction sets set per contact name (Simulator::SetFrictionSet): (first, second) collider →
  /// set, first < second; usually empty.
  std::vector<std::pair<std::pair<int, int>, FrictionSet>> pair_sets;
  /// Per body: the external wrench; any_wrench: one of them is set (a world without one skips
  /// the work in ComputeMidpoints).
  std::vector<BodyWrench> wrench;
  bool any_wrench = false;

  // --- derived from scene by BuildCaches
  /// Per body: M⁻¹ (10).
  std::vector<BodyInertia> inertia;
  /// The static plane colliders.
  std::vector<int> planes;
  /// Whether two colliders that are not planes can meet (two bodies with colliders, or a body and
  /// a static collider that is not a plane): without, the broad phase's sweep is skipped.
  bool needs_sweep = false;
  /// Per collider: its pose on its body has a rotation (not identity). Bytes, not
  /// std::vector<bool>: read per collider and step.
  std::vector<std::uint8_t> collider_rotated;
  /// Per collider: BoundingRadius of its shape padded by kContactHysteresis [m].
  std::vector<double> bounding_radius;
  /// Per collider: the world pose of a static collider (identity for a collider on a body).
  std::vector<Eigen::Isometry3d> static_pose;

  /// Rebuilds the derived arrays from scene (keeps pair_sets and wrench).
  void BuildCaches();
  /// The law of the collider pair (first < second) with the overrides of pair_sets.
  ContactLaw PairLaw(int first, int second) const {
    ContactLaw law = CombineLaws(scene.colliders[static_cast<std::size_t>(first)],
                                 scene.colliders[static_cast<std::size_t>(second)]);
    for (const auto& [pair, set] : pair_sets) {  // usually empty
      if (pair.first == first && pair.second == second) law.friction_set = set;
    }
    return law;
  }
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_MODEL_H_
