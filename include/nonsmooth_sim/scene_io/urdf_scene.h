// A core Scene from a URDF (urdfdom model + TinyXML2 extension tags). Conversion only, no physics,
// no ROS. The user's guide with examples is docs/urdf.md.
//
// Bodies and the static world:
//  - a free body is a link that is the root or hangs on a `floating` joint, together with the
//    links fixed to it (recursively, by `fixed` joints). Its body frame K has its origin at the
//    centre of mass S and the axes of that link; RigidBody::com_in_link is S in that link's frame.
//    Each <inertial> is re-expressed in link axes (inertia given in the rotated <inertial><origin>
//    frame R: Θ_link = R Θ Rᵀ) and the links merged by fixed joints combine exactly:
//      m = Σ mᵢ,  c = Σ mᵢ cᵢ / m,  Θ_S = Σ [Θᵢ + mᵢ (|dᵢ|² 1 − dᵢ dᵢᵀ)],  dᵢ = cᵢ − c
//    (parallel-axis theorem; cᵢ and Θᵢ in the body link's frame and axes).
//  - a root link without <inertial> (e.g. `world`) is the static world: its collisions and those
//    of the links fixed to it (recursively) are world colliders (body kWorld) at their world pose.
//    Such static links must not have an <inertial>.
//  - links on other joint types (revolute, prismatic, ...) are reported in UrdfScene::warnings and
//    skipped; floating joints below them still make free bodies.
//  - bodies are listed in the document order of their links.
//
// Colliders:
//  - <collision> geometry <sphere radius>, <cylinder radius length> (axis z, half_length =
//    length/2), <box size> (half_extents = size/2); the pose is the collision <origin> in K (the
//    link frame shifted to S, link axes) or in the world. <mesh>: reported and skipped.
//  - <nonsmooth_sim reference="link"><collision name="c"><ellipsoid semi_axes="a b c"/> |
//    <capsule radius="r" length="l"/> | <plane/></collision></nonsmooth_sim> replaces the URDF
//    geometry of the link's collision "c" (l = segment between the cap centres, along z; the plane
//    is the half-space z ≤ 0 of the collision frame, world links only).
//  - names: the <collision name>, or "<link>_collision<k>" (k = 1, 2, ... its position in the
//    link) when empty; every name once in the scene; "ground" is the ground plane's when
//    options.ground (GroundPlane(), the last collider).
//  - order: world colliders, then each body's (its own link's first), then the ground.
//  - a pair of shape types that can meet (on different bodies, or a body and the world) but has
//    no collide function (core/collision/collision.h) is reported in warnings.
//
// Contact laws (per collider, from the tags of its own link):
//      <gazebo reference="link"><collision><surface><friction>
//        <ode><mu>μ</mu></ode>
//        <torsional><coefficient>μ_τ</coefficient><patch_radius>R</patch_radius></torsional>
//      </friction></surface></collision></gazebo>
//    with SDF's defaults (μ = 1, μ_τ = 1, R = 0). Gazebo bounds the drilling torque by
//    μ_τ·(3πR/16)·λ_N, the core by R̄·μ·λ_N, so R̄ = 3πR/16 · μ_τ/μ (eq. (50); μ_τ = μ gives the
//    paper's R̄). Restitution ε of (14) and the friction set:
//      <nonsmooth_sim reference="link"><restitution>ε</restitution>
//        <friction_set>exact</friction_set></nonsmooth_sim>
//    Options replace μ (and μ_τ) and R of every link; options.friction_set is the set of the links
//    without <friction_set>.
//
// Errors: a malformed or inconsistent URDF throws UrdfError with one line naming the element and
// the reason (not XML, no inertial on a body with collisions, mass ≤ 0, inertia not positive
// definite, degenerate shapes, NaN or Inf in any number, a typo in a <nonsmooth_sim> block, a
// collision name used twice, a static link with mass, ...). Overlapping bodies are not checked
// here (the simulator reports them).
#ifndef NONSMOOTH_SIM_SCENE_IO_URDF_SCENE_H_
#define NONSMOOTH_SIM_SCENE_IO_URDF_SCENE_H_

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim::scene_io {

/// A malformed or inconsistent URDF. what(): one line, "urdf: <element>: <reason>".
class UrdfError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct UrdfSceneOptions {
  double gravity = 9.81;  ///< g [m/s²], finite, ≥ 0, acting along -z
  /// friction set of the links without <nonsmooth_sim><friction_set>
  FrictionSet friction_set = FrictionSet::kSphere;
  std::optional<double> mu;  ///< replaces ode/mu and torsional/coefficient of every link, ≥ 0
  std::optional<double> contact_radius;  ///< replaces torsional/patch_radius R [m], ≥ 0
  bool ground = true;  ///< append the core's GroundPlane() (z = 0, "ground") as the last collider
};

struct UrdfScene {
  /// Bodies, colliders and laws; initial_state holds every body at its URDF pose, at rest
  /// (initial_state.h applies a configured start).
  Scene scene;
  /// Per body: its parameters when it is a Tippe-Top (one sphere collider whose name ends in
  /// "big_sphere" and one ending in "peg_sphere", both on the link's z axis through the centre
  /// of mass, inertia diagonal with A = B), so that its start can be exactly the core's
  /// TippeTopInitialState. contact_radius is R of the options or of the link's patch_radius.
  std::vector<std::optional<TippeTopParameters>> tippe_top;
  /// Per body: the links merged into it by fixed joints, in document order (its own link,
  /// RigidBody::name, excluded).
  std::vector<std::vector<std::string>> merged_links;
  /// What was skipped and why, one line each ("urdf: ...").
  std::vector<std::string> warnings;
};

/// The scene of the URDF text `urdf_xml`. Throws UrdfError, and std::invalid_argument naming the
/// option for options out of range.
UrdfScene SceneFromUrdf(const std::string& urdf_xml, const UrdfSceneOptions& options = {});

/// The scene of the URDF file `path`. Throws UrdfError ("urdf: <path>: ...") also when the file
/// does not exist or cannot be read.
UrdfScene LoadUrdfFile(const std::string& path, const UrdfSceneOptions& options = {});

/// Throws std::invalid_argument naming the option and its range.
void ValidateUrdfSceneOptions(const UrdfSceneOptions& options);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_URDF_SCENE_H_
