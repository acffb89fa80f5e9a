// The start of the world's bodies: one API for every route to it. The node's ~initial/...
// (one body: inclination, spin, pose, velocities) and ~initial_state/bodies/<link>/... (any body,
// config/<scene>.yaml loaded as parameters) become one StartSpec, and every start goes through
// StartState (World::Reset, the ~reset service: InitialState for the one body it moves).
//
// inclination θ and spin ω give the Tippe-Top start of ../shared/reference/tippe-top.md: e3
// tilted about the world x axis by θ, spin ω about the tilted e3, centre of mass at rest, the
// lowest sphere touching the ground. For a body that is a Tippe-Top (UrdfScene::tippe_top) this is
// exactly the core's TippeTopInitialState. position, orientation and the velocities, when set,
// replace the corresponding part (with an orientation but no position the body is lowered or
// raised onto the ground again).
#ifndef NONSMOOTH_SIM_WORLD_INITIAL_CONDITIONS_H_
#define NONSMOOTH_SIM_WORLD_INITIAL_CONDITIONS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::world {

// Bounds (scene_io/initial_state.h, the same for every start of the node and of `simulate`):
// position coordinates within kMaxInitialCoordinate, |v| ≤ kMaxInitialSpeed, |spin| and |ω| ≤
// kMaxInitialAngularSpeed, so that the kinetic energy is finite and Δt·|ω| can be checked.
struct InitialConditions {
  std::optional<double> inclination;               ///< θ [rad], in [0, π]
  std::optional<double> spin;                      ///< ω about e3 [rad/s], |ω| ≤ 1e4
  std::optional<Eigen::Vector3d> position;         ///< r_S, world frame [m], |x|, |y|, |z| ≤ 1e3
  std::optional<Eigen::Quaterniond> orientation;   ///< link axes → world, non-zero (normalised)
  std::optional<Eigen::Vector3d> linear_velocity;  ///< v_S in the world frame [m/s], |v| ≤ 1e3
  std::optional<Eigen::Vector3d> angular_velocity; ///< K_ω in the link axes [rad/s], |ω| ≤ 1e4
};

/// Each field of `overrides` that is set, else the one of `defaults`.
InitialConditions Merge(const InitialConditions& defaults, const InitialConditions& overrides);

/// Throws std::invalid_argument naming the field and the reason (NaN/Inf, θ outside [0, π],
/// zero quaternion, a value beyond its bound above).
void ValidateInitialConditions(const InitialConditions& initial);

/// The start of every body: `body` from `initial` (unset θ and ω: the core's
/// TippeTopInitialConditions defaults), the other bodies at their URDF pose, at rest. A body that
/// is not a Tippe-Top, with no field of `initial` set, stays at its URDF pose, at rest.
/// Throws std::invalid_argument (see ValidateInitialConditions) and std::out_of_range for `body`.
std::vector<BodyState> InitialState(const scene_io::UrdfScene& urdf, int body,
                                    const InitialConditions& initial);

/// The start of a URDF's bodies: `conditions` for `body` (InitialState), then the per-link
/// states of `bodies` over it (scene_io::ApplyInitialState).
struct StartSpec {
  int body = 0;                       ///< the body `conditions` move (an index into the URDF)
  InitialConditions conditions;       ///< ~initial/...
  scene_io::InitialStateSpec bodies;  ///< ~initial_state/bodies/<link>/... (or a YAML file)
};

/// The start every route goes through: InitialState(urdf, start.body, start.conditions) with the
/// states of start.bodies applied over it. Throws std::invalid_argument naming the field.
std::vector<BodyState> StartState(const scene_io::UrdfScene& urdf, const StartSpec& start);

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_INITIAL_CONDITIONS_H_
