// The XML side of the URDF conversion (TinyXML2): well-formedness, strict numbers everywhere, and
// the extension tags urdfdom ignores (Gazebo's <gazebo reference=...> surface friction, our
// <nonsmooth_sim reference=...> restitution). See urdf_scene.h for the rules.
#ifndef NONSMOOTH_SIM_NODE_URDF_XML_H_
#define NONSMOOTH_SIM_NODE_URDF_XML_H_

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace nonsmooth_sim::node {

/// Contact parameters of one link's collisions, with SDF's defaults where a tag is absent.
struct LinkSurface {
  double mu = 1.0;                     ///< ode/mu (SDF default 1), ≥ 0
  double torsional_coefficient = 1.0;  ///< torsional/coefficient (SDF default 1), ≥ 0
  bool has_torsional_coefficient = false;
  double patch_radius = 0.0;           ///< torsional/patch_radius R [m] (SDF default 0), ≥ 0
  double restitution = 0.0;            ///< ε of (14), in [0, 1]
};

struct UrdfXml {
  std::map<std::string, LinkSurface> surfaces;  ///< by link name; absent = defaults
  std::vector<std::string> warnings;
};

/// Parses `xml` and checks it (throws UrdfError, see urdf_scene.h): well-formed XML with a <robot>
/// root; every numeric attribute made of finite numbers (the count each URDF attribute needs);
/// masses, sphere/cylinder radii, lengths and box sizes > 0; every <inertial> with a <mass> and an
/// <inertia>; extension values in range. Returns the extension data.
UrdfXml ParseUrdfXml(const std::string& xml);

/// Parses one number exactly (no trailing characters, finite); false otherwise.
bool ParseFiniteNumber(std::string_view text, double* value);

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_URDF_XML_H_
