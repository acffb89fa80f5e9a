// A core Scene from a URDF (urdfdom model + TinyXML2 extension tags). Conversion only, no physics,
// no ROS. The user's guide with examples is docs/urdf.md.
//
// Bodies and the static world (the grouping: src/scene_io/link_groups.h):
//  - a free body is a link that is the root or hangs on a `floating` joint, together with the
//    links fixed to it (recursively, by `fixed` joints, and by `revolute` or `prismatic` joints
//    whose limits are equal, lower = upper: they cannot move, so the link is held at that
//    position, reported in UrdfScene::warnings). Its body frame K has its origin at the
//    centre of mass S and the axes of that link; RigidBody::com_in_link is S in that link's frame.
//    Each <inertial> is re-expressed in link axes (inertia given in the rotated <inertial><origin>
//    frame R: Θ_link = R Θ Rᵀ) and the links merged by fixed joints combine exactly:
//      m = Σ mᵢ,  c = Σ mᵢ cᵢ / m,  Θ_S = Σ [Θᵢ + mᵢ (|dᵢ|² 1 − dᵢ dᵢᵀ)],  dᵢ = cᵢ − c
//    (parallel-axis theorem; cᵢ and Θᵢ in the body link's frame and axes).
//  - the root is a free body (named after it) when it or a link fixed to it has an <inertial>:
//    the massless root exporters write (`base_footprint` above `base_link`) is lumped with the
//    links fixed to it, as Gazebo lumps it. Otherwise, and always when it is named `world`, the
//    root is the static world: its collisions and those of the links fixed to it (recursively)
//    are world colliders (body kWorld) at their world pose; such static links must not have an
//    <inertial>. Links on floating joints below the root are free bodies of their own either way.
//  - the simulator has no joints: a link on a `revolute`, `continuous`, `prismatic` or `planar`
//    joint that can move is refused (UrdfError naming the joint, its type and the link) when it
//    or a link fixed to it has an <inertial> or a <collision>; without either it is left out with
//    a warning. Floating joints below a left-out link still make free bodies (at the moving
//    joint's zero position).
//  - unless the user holds the joint rigid (as Drake's Joint::Lock):
//      <nonsmooth_sim joint="j"><hold position="q"/></nonsmooth_sim>
//    (q optional, default 0: rad for revolute and continuous, m along the axis for prismatic; a
//    planar joint only at 0), or options.hold_joints (at 0, or at the block's q). A held joint is
//    merged as one with lower = upper, at q, with one warning per joint. Refused with one line: a
//    name that is no joint (the joints that move listed), a fixed or floating joint, q outside
//    [lower, upper] of a revolute or prismatic joint, a planar joint's q ≠ 0.
//  - bodies are listed in the document order of their links.
//
// Colliders:
//  - <collision> geometry <sphere radius>, <cylinder radius length> (axis z, half_length =
//    length/2), <box size> (half_extents = size/2); the pose is the collision <origin> in K (the
//    link frame shifted to S, link axes) or in the world. <mesh filename scale>: the convex hull
//    of its vertices (mesh_source.h: package://, file:// and paths; STL, OBJ, DAE; at most
//    options.max_hull_vertices vertices), a convex_hull shape; the body's mass and inertia stay
//    its <inertial>. A mesh that cannot be a hull (missing, empty, a device, FIFO or directory,
//    larger than options.max_bytes, unreadable, flat, scale out of [kMinMeshScale,
//    kMaxMeshScale], a package:// path leaving its package) throws UrdfError naming the link's
//    collision and the file.
//  - <nonsmooth_sim reference="link"><collision name="c"><ellipsoid semi_axes="a b c"/> |
//    <capsule radius="r" length="l"/> | <plane/></collision></nonsmooth_sim> replaces the URDF
//    geometry of the link's collision "c" (l = segment between the cap centres, along z; the plane
//    is the half-space z ≤ 0 of the collision frame, world links only).
//  - names: the <collision name>, or "<link>_collision<k>" (k = 1, 2, ... its position in the
//    link) when empty; every name once in the scene; "ground" is the ground plane's when
//    options.ground (GroundPlane(), the last collider).
//  - order: world colliders, then each body's (its own link's first), then the ground.
//  - the scene collides with options.collision_table (Scene::collision_table): a pair of shape
//    types that can meet (on different bodies, or a body and the world) but has no function in it
//    (core/collision/collision_table.h) is reported in warnings.
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
//    The rolling resistance μ_r [m] (rolling_contact_solver.h; default 0, none):
//      <nonsmooth_sim reference="link"><rolling_resistance>μ_r</rolling_resistance></nonsmooth_sim>
//    or Bullet's <gazebo reference="link"><collision><surface><friction><bullet>
//      <rolling_friction>μ_r</rolling_friction></bullet>... (or <rolling_friction> in <gazebo>);
//    the <nonsmooth_sim> value wins. Options replace μ (and μ_τ), R and μ_r of every link;
//    options.friction_set is the set of the links without <friction_set>.
//
// Errors: a malformed or inconsistent URDF throws UrdfError with one line naming the element and
// the reason (not XML, no inertial on a body with collisions, mass ≤ 0, inertia not positive
// definite, degenerate shapes, NaN or Inf in any number, a typo in a <nonsmooth_sim> block, a
// collision name used twice, a static link with mass, a link with mass or collisions on a joint
// that can move and is not held, a hold of a joint that does not exist or does not move, ...). Overlapping bodies are not checked
// here (the simulator reports them).
//
// Bounds: what loads is a simulable rigid body. Finite is not enough (mass 4.9e-324 passes "> 0"
// and makes M⁻¹ infinite at the first step), so every number has a range wide enough for any
// body on a desk or a factory floor and narrow enough that M⁻¹, G = W M⁻¹ Wᵀ, the friction radii
// and the energy stay finite with room to spare (the constants below; docs/urdf.md, "Bounds"):
//  - mass of each <inertial> and of each body (links merged) in [kMinMass, kMaxMass];
//  - the principal moments of each <inertia> and each body (eigenvalues of Θ) > 0 and each at most
//    the sum of the other two (the triangle inequality every rigid body satisfies,
//    I₃ = ∫(x² + y²) ≤ ∫(y² + z²) + ∫(x² + z²)), up to kInertiaTriangleTolerance relative;
//  - every radius of gyration √(Iᵢ/m) in [kMinGyrationRadius, kMaxGyrationRadius], and for a body
//    with colliders the largest at most kGyrationSizeFactor times the body's extent (the farthest
//    point of its collision shapes from S): a body's mass cannot lie far outside what it touches
//    with;
//  - every <origin xyz> coordinate in links and joints, and every composed pose (a body's start,
//    a collider relative to its body or in the world), |x|, |y|, |z| ≤ kMaxCoordinate;
//  - collision radii, lengths, box sizes, semi-axes in [kMinLength, kMaxLength] (a capsule's
//    length in [0, kMaxLength]);
//  - μ, μ₂ and μ_τ in [0, kMaxFriction]; the patch radius R (or the option) in [0, kMaxLength] and
//    at most the bounding radius of each shape of a free body it applies to (the contact patch lies
//    on the shape); R̄ = 3πR/16·μ_τ/μ ≤ kMaxLength; ε in [0, 1]; μ_r in [0, kMaxLength];
//    gravity in [0, kMaxGravity];
//  - sizes (bounded_input.h): the text at most options.max_bytes, names at most kMaxNameLength
//    bytes, at most kMaxCollisionsPerModel <collision> elements; a file must be a regular file.
#ifndef NONSMOOTH_SIM_SCENE_IO_URDF_SCENE_H_
#define NONSMOOTH_SIM_SCENE_IO_URDF_SCENE_H_

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/one_line.h"

namespace nonsmooth_sim::scene_io {

/// The loader's bounds (see "Bounds" above).
inline constexpr double kMinMass = 1e-6;  ///< [kg]: a grain of sand; M⁻¹ ≤ 1e6 1/kg
inline constexpr double kMaxMass = 1e6;   ///< [kg]: a thousand tonnes
/// |x|, |y|, |z| of every origin and composed pose [m]: 1 km keeps positions resolved to 1e-13 m
inline constexpr double kMaxCoordinate = 1e3;
inline constexpr double kMinLength = 1e-5;  ///< radii, lengths, sizes [m]: 10 µm
inline constexpr double kMaxLength = 1e3;   ///< [m]
inline constexpr double kMaxFriction = 1e3;  ///< μ, μ₂, μ_τ (the core's stability tests reach 1e3)
inline constexpr double kMaxGravity = 1e3;   ///< g [m/s²], about 100 g
/// Relative slack of the triangle inequality of the principal moments: rounded inertia entries of
/// a flat body (I₃ = I₁ + I₂ exactly) must still load.
inline constexpr double kInertiaTriangleTolerance = 1e-3;
inline constexpr double kMinGyrationRadius = 1e-6;  ///< √(Iᵢ/m) [m]
inline constexpr double kMaxGyrationRadius = 1e3;   ///< √(Iᵢ/m) [m]
/// √(I_max/m) ≤ this × the body's extent (a thin ring of the body's size has √(I/m) = extent).
inline constexpr double kGyrationSizeFactor = 100.0;

/// The largest UrdfSceneOptions::max_bytes a user may configure [bytes]: 256 MiB.
inline constexpr std::size_t kMaxInputBytesOption = std::size_t{256} << 20;

/// A malformed or inconsistent URDF. what(): one line, "urdf: <element>: <reason>" (control
/// characters of the quoted input escaped, one_line.h).
class UrdfError : public std::invalid_argument {
 public:
  explicit UrdfError(const std::string& what) : std::invalid_argument(OneLine(what)) {}
};

struct UrdfSceneOptions {
  double gravity = 9.81;  ///< g [m/s²], in [0, kMaxGravity], acting along -z
  /// friction set of the links without <nonsmooth_sim><friction_set>
  FrictionSet friction_set = FrictionSet::kSphere;
  /// replaces ode/mu and torsional/coefficient of every link, in [0, kMaxFriction]
  std::optional<double> mu;
  /// replaces torsional/patch_radius R [m], in [0, kMaxLength] and at most the bounding radius of
  /// every collision shape of a free body (checked by the loader against the scene)
  std::optional<double> contact_radius;
  /// replaces the rolling resistance μ_r of every link [m], in [0, kMaxLength]
  std::optional<double> rolling_resistance;
  bool ground = true;  ///< append the core's GroundPlane() (z = 0, "ground") as the last collider
  /// [bytes] of the URDF text or file, at most this (refused before parsing; bounded_input.h);
  /// in [1, kMaxInputBytesOption]
  std::size_t max_bytes = kMaxInputBytes;
  /// the folder of <mesh filename>s given as relative paths; empty: LoadUrdfFile uses the URDF
  /// file's folder, SceneFromUrdf the current folder
  std::string mesh_directory;
  /// where package:// meshes are searched (mesh_source.h); unset: the environment's
  /// ROS_PACKAGE_PATH
  std::optional<std::string> ros_package_path;
  /// vertices of a mesh's convex hull, at most (as MuJoCo's maxhullvert), in
  /// [4, kMaxHullVerticesBound]
  int max_hull_vertices = kDefaultMaxHullVertices;
  /// moving joints (revolute, continuous, prismatic, planar) held rigid at 0, or at the position
  /// of the URDF's <nonsmooth_sim joint="j"><hold position="q"/> for the same joint: merged as a
  /// joint with lower = upper (a warning each). A name that is not a moving joint of the URDF
  /// throws UrdfError; each name at most kMaxNameLength bytes.
  std::vector<std::string> hold_joints;
  /// the pair functions of the scene (its Scene::collision_table): the core's closed forms, or
  /// with RegisterFclPairs (collision_fcl/fcl_pairs.h) also the convex pairs without one
  CollisionTable collision_table = CollisionTable::Defaults();
};

/// A link without a body of its own, for TF: merged into body `body` by fixed joints (`pose`: its
/// frame in that body's link frame) or fixed to the world (body kWorld, `pose` in the world).
struct FixedLink {
  std::string name;
  int body = kWorld;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

struct UrdfScene {
  std::string robot_name;  ///< <robot name="...">
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
  /// Every link that is not a body's own (the static world's, those merged into bodies), in
  /// document order per group: fixed transforms for TF.
  std::vector<FixedLink> fixed_links;
  /// What was left out or changed and why (a joint held rigid, a massless link on a moving
  /// joint, anisotropic friction, ...), one line each ("urdf: ...").
  std::vector<std::string> warnings;
};

/// The scene of the URDF text `urdf_xml`. Throws UrdfError, and std::invalid_argument naming the
/// option for options out of range.
UrdfScene SceneFromUrdf(const std::string& urdf_xml, const UrdfSceneOptions& options = {});

/// The scene of the URDF file `path`. Throws UrdfError ("urdf: <path>: ...") also when the file
/// does not exist, cannot be read, is not a regular file (a device, a FIFO: never opened for a
/// wait) or has more than options.max_bytes bytes (bounded_input.h).
UrdfScene LoadUrdfFile(const std::string& path, const UrdfSceneOptions& options = {});

/// Throws std::invalid_argument naming the option and its range.
void ValidateUrdfSceneOptions(const UrdfSceneOptions& options);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_URDF_SCENE_H_
