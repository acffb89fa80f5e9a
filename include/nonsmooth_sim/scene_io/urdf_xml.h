// The XML side of the URDF loader (TinyXML2): well-formedness, strict numbers everywhere, and the
// extension tags urdfdom ignores: Gazebo's <gazebo reference="link"> surface friction and our
// <nonsmooth_sim reference="link"> block (restitution, friction set, shapes URDF cannot express).
// See urdf_scene.h for the rules and docs/urdf.md for the user's view.
#ifndef NONSMOOTH_SIM_SCENE_IO_URDF_XML_H_
#define NONSMOOTH_SIM_SCENE_IO_URDF_XML_H_

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nonsmooth_sim/core/friction_law.h"
#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim::scene_io {

/// Contact parameters of one link's collisions, with SDF's defaults where a tag is absent.
struct LinkSurface {
  double mu = 1.0;                     ///< ode/mu (SDF default 1), in [0, kMaxFriction]
  double torsional_coefficient = 1.0;  ///< torsional/coefficient μ_τ (SDF default 1), same
  double patch_radius = 0.0;           ///< torsional/patch_radius R [m] (default 0), ≤ kMaxLength
  double restitution = 0.0;            ///< ε of (14), in [0, 1]
  /// <nonsmooth_sim><rolling_resistance> μ_r [m], in [0, kMaxLength]; unset: rolling_friction
  std::optional<double> rolling_resistance;
  /// <gazebo>'s rolling_friction (SDF's bullet/rolling_friction, or a direct child) [m], in
  /// [0, kMaxLength] (default 0: no rolling resistance)
  double rolling_friction = 0.0;
  /// <nonsmooth_sim><friction_set>; unset: the loader option UrdfSceneOptions::friction_set
  std::optional<FrictionSet> friction_set;
};

/// <body_of_revolution axis="x y z" tolerance="τ"/>: the collision's <mesh> as a smooth body of
/// revolution (mesh/mesh_revolution.h).
struct RevolutionRequest {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< in the mesh's frame, not 0
  std::optional<double> tolerance;                  ///< [m], in [kMinLength, kMaxLength]
};

/// <nonsmooth_sim reference="link"><collision name="c"><ellipsoid|capsule|plane .../></collision>:
/// a shape that replaces the URDF geometry of the link's collision "c" (its <origin> is kept);
/// or <body_of_revolution/>, which tells how to read its <mesh>.
struct ShapeOverride {
  Shape shape;
  std::optional<RevolutionRequest> revolution;  ///< set: `shape` is unused
  /// The element, for error lines: nonsmooth_sim reference="b" > collision "c" > plane (line 7)
  std::string where;
};

/// <nonsmooth_sim joint="j"><hold position="q"/></nonsmooth_sim>: the user's opt-in to hold the
/// moving joint "j" rigid at q (no position: 0), merged as a joint with lower = upper is. Checked
/// against the model by the loader (src/scene_io/link_groups.h: the joint exists and moves, q
/// within its limits).
struct JointHold {
  std::string joint;
  std::optional<double> position;  ///< rad (revolute, continuous) or m (prismatic); unset: 0
  std::string where;               ///< nonsmooth_sim joint="j" > hold (line 7), for error lines
  int line = 0;                    ///< the line of the <nonsmooth_sim joint="j"> block
};

/// One <nonsmooth_sim reference=...> block, for the checks that need the model (does the link
/// exist).
struct ExtensionBlock {
  std::string link;
  std::string where;  ///< nonsmooth_sim reference="b" (line 3)
};

struct UrdfXml {
  std::vector<std::string> link_order;          ///< <link name> in document order
  std::map<std::string, LinkSurface> surfaces;  ///< by link name; absent = defaults
  /// by link name, then collision name
  std::map<std::string, std::map<std::string, ShapeOverride>> shapes;
  std::vector<ExtensionBlock> extension_blocks;  ///< every <nonsmooth_sim reference> block
  std::vector<JointHold> joint_holds;  ///< every <nonsmooth_sim joint> block; one per joint
  std::vector<std::string> gazebo_references;    ///< every <gazebo reference> (links or joints)
  std::vector<std::string> warnings;
};

/// Parses `xml` and checks it (throws UrdfError, see urdf_scene.h): well-formed XML with a <robot>
/// root; every numeric attribute of links and joints made of finite numbers (the count each URDF
/// attribute needs); masses, sphere/cylinder radii, lengths and box sizes > 0; every <inertial>
/// with a <mass> and an <inertia>; the element-level bounds of urdf_scene.h ("Bounds": origins,
/// masses, collision sizes, friction μ/μ₂/μ_τ in [0, kMaxFriction], patch radius in
/// [0, kMaxLength]); the <nonsmooth_sim> blocks strictly: known elements and attributes only,
/// values in range, shapes not degenerate, one <hold> per joint. Returns the extension data.
UrdfXml ParseUrdfXml(const std::string& xml);

/// Parses one number exactly (no trailing characters, finite); false otherwise.
bool ParseFiniteNumber(std::string_view text, double* value);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_URDF_XML_H_
