// A core Scene from a URDF: the ROS node's scene description. Conversion only, no physics.
//
// Rules (README, "Scene from URDF"):
//  - every link with an <inertial> that is the root or hangs on a `floating` joint is a free body;
//    its body frame has its origin at the centre of mass and the link's axes. Inertia given in the
//    <inertial><origin> frame (rpy) is re-expressed in link axes: Θ_link = R Θ Rᵀ; the origin's
//    xyz becomes RigidBody::com_in_link.
//  - its <collision> spheres touch the ground plane z = 0; other geometry and links on other
//    joint types are reported in UrdfScene::warnings and skipped.
//  - the contact law of a link's spheres comes from Gazebo's extension
//      <gazebo reference="link"><collision><surface><friction>
//        <ode><mu>μ</mu></ode>
//        <torsional><coefficient>μ_τ</coefficient><patch_radius>R</patch_radius></torsional>
//      </friction></surface></collision></gazebo>
//    with SDF's defaults (μ = 1, μ_τ = 1, R = 0). Gazebo bounds the drilling torque by
//    μ_τ·(3πR/16)·λ_N, the core by R̄·μ·λ_N, so R̄ = 3πR/16 · μ_τ/μ (eq. (50); μ_τ = μ gives the
//    paper's R̄). Restitution ε of (14): <nonsmooth_sim reference="link"><restitution>ε</restitution>.
//  - a malformed or inconsistent URDF throws UrdfError with one line naming the element and the
//    reason (not XML, no inertial, mass ≤ 0, inertia not positive definite, radius ≤ 0, NaN or
//    Inf in any number, ...).
#ifndef NONSMOOTH_SIM_NODE_URDF_SCENE_H_
#define NONSMOOTH_SIM_NODE_URDF_SCENE_H_

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim::node {

/// A malformed or inconsistent URDF. what(): one line, "urdf: <element>: <reason>".
class UrdfError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct UrdfSceneOptions {
  double gravity = 9.81;                            ///< g [m/s²], ≥ 0, acting along -z
  FrictionSet friction_set = FrictionSet::kSphere;  ///< law of every contact
  std::optional<double> mu;              ///< replaces ode/mu and torsional/coefficient, ≥ 0
  std::optional<double> contact_radius;  ///< replaces torsional/patch_radius R [m], ≥ 0
};

struct UrdfScene {
  /// Bodies, spheres and laws; initial_state holds every body at its URDF pose, at rest
  /// (see initial_conditions.h for the configured start).
  Scene scene;
  /// Per body: its parameters when it is a Tippe-Top (spheres "big_sphere" and "peg_sphere" on
  /// the link's z axis through the centre of mass, inertia diagonal with A = B), so that its start
  /// is exactly the core's TippeTopInitialState.
  std::vector<std::optional<TippeTopParameters>> tippe_top;
  /// What was skipped and why, one line each.
  std::vector<std::string> warnings;
};

/// Throws UrdfError. Options are validated too (std::invalid_argument naming the option).
UrdfScene SceneFromUrdf(const std::string& urdf_xml, const UrdfSceneOptions& options = {});

/// Throws std::invalid_argument naming the option and its range.
void ValidateUrdfSceneOptions(const UrdfSceneOptions& options);

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_URDF_SCENE_H_
