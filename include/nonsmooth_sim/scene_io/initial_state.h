// Initial conditions of a scene's bodies from YAML (yaml-cpp). The format, read by other programs
// too, is exactly:
//
//   bodies:
//     <link>:                                  # a free body of the scene (RigidBody::name)
//       position: [x, y, z]                    # origin of the LINK frame in the world [m]
//       orientation: [qx, qy, qz, qw]          # link axes → world, normalised, non-zero
//       linear_velocity: [vx, vy, vz]          # v_S of the centre of mass, world axes [m/s]
//       angular_velocity: [wx, wy, wz]         # K_ω, link (= body) axes [rad/s]
//
// Every key is optional; what is absent keeps the default state (the URDF pose, at rest). The
// core's BodyState holds the centre of mass S, so with R the orientation and c =
// RigidBody::com_in_link:
//   r_S = position + R c,   position = r_S − R c.
// Given only an orientation, the link frame keeps its default origin and turns about it.
// Anything else (unknown keys or links, wrong lengths, NaN/Inf, a zero quaternion, values beyond
// the bounds below) is an error.
//
// Bounds (every start: this file, the node's ~initial_state, ~initial/... and ~reset): finite is
// not enough (a spin of 1e300 rad/s has an infinite kinetic energy), so each coordinate of a
// position is within kMaxInitialCoordinate (the loader's kMaxCoordinate), |v| ≤ kMaxInitialSpeed
// and |ω| ≤ kMaxInitialAngularSpeed. With the loader's bounds on mass and inertia the kinetic
// energy ½m|v|² + ½ωᵀΘω stays below 1e20 J, and Δt·|ω| (the explicit gyroscopic term's safety
// measure, simulator.h) at most 100 at the largest Δt. The limits are far beyond the shipped
// scenes (at most 300 rad/s and 0.44 m/s).
#ifndef NONSMOOTH_SIM_SCENE_IO_INITIAL_STATE_H_
#define NONSMOOTH_SIM_SCENE_IO_INITIAL_STATE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/scene_io/one_line.h"

namespace nonsmooth_sim::scene_io {

inline constexpr double kMaxInitialCoordinate = 1e3;     ///< |x|, |y|, |z| of a position [m]
inline constexpr double kMaxInitialSpeed = 1e3;          ///< |v_S| [m/s]
inline constexpr double kMaxInitialAngularSpeed = 1e4;   ///< |ω| [rad/s]

/// Throws std::invalid_argument "<what>: <reason>" unless the value is within its bound above:
/// a position's coordinates, a linear or an angular velocity's norm (NaN and Inf fail too).
void CheckInitialPosition(const std::string& what, const Eigen::Vector3d& position);
void CheckInitialLinearVelocity(const std::string& what, const Eigen::Vector3d& velocity);
void CheckInitialAngularVelocity(const std::string& what, const Eigen::Vector3d& velocity);

/// A malformed initial state. what(): one line,
/// "initial state: bodies.<link>.<key> (line n): <reason>; <what is allowed>" (control characters
/// of the quoted input escaped, one_line.h).
class InitialStateError : public std::invalid_argument {
 public:
  explicit InitialStateError(const std::string& what) : std::invalid_argument(OneLine(what)) {}
};

/// The start of one body as written (see the top of this file); each part optional.
struct BodyInitialState {
  std::optional<Eigen::Vector3d> position;          ///< link frame origin, world [m]
  std::optional<Eigen::Quaterniond> orientation;    ///< link axes → world, unit
  std::optional<Eigen::Vector3d> linear_velocity;   ///< v_S, world [m/s]
  std::optional<Eigen::Vector3d> angular_velocity;  ///< K_ω, link axes [rad/s]
  int line = 0;  ///< line of the body's key in the YAML text (for error lines), 0 if none
};

/// By body (link) name.
using InitialStateSpec = std::map<std::string, BodyInitialState>;

/// Parses and checks the YAML text (keys, lengths, finite numbers, non-zero quaternions, the
/// bounds above; the orientation is normalised). An empty document is an empty spec. Throws
/// InitialStateError.
InitialStateSpec ParseInitialStateYaml(const std::string& yaml_text);

/// `defaults` (one per body, usually scene.initial_state) with every part given in `spec`
/// replaced (see the top of this file). Throws InitialStateError for a name that is not a body
/// of the scene (listing the bodies) and for a part of `spec` or a resulting centre of mass
/// beyond the bounds above, std::invalid_argument if `defaults` does not fit the scene.
std::vector<BodyState> ApplyInitialState(const Scene& scene,
                                         const std::vector<BodyState>& defaults,
                                         const InitialStateSpec& spec);

/// ApplyInitialState(scene, scene.initial_state, ParseInitialStateYaml(yaml_text)).
std::vector<BodyState> InitialStateFromYaml(const Scene& scene, const std::string& yaml_text);

/// The same from a file; errors read "initial state: <path>: ...", also for a missing file.
std::vector<BodyState> InitialStateFromYamlFile(const Scene& scene, const std::string& path);

/// The inverse: every key of every body, numbers with 17 significant digits. Throws
/// std::invalid_argument if `state` does not fit the scene or is not finite (ValidateState).
std::string InitialStateToYaml(const Scene& scene, const std::vector<BodyState>& state);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_INITIAL_STATE_H_
