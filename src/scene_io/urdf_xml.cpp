// Strict XML checks and extension tags of a URDF (TinyXML2). See urdf_xml.h.
#include "nonsmooth_sim/scene_io/urdf_xml.h"

#include <tinyxml2.h>

#include <charconv>
#include <cmath>
#include <initializer_list>
#include <sstream>

#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/format.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {
namespace {

using tinyxml2::XMLElement;

// "link "tippe_top" > inertial > mass" (robot excluded), for error lines.
std::string Describe(const XMLElement* element) {
  std::string path;
  for (const XMLElement* e = element; e != nullptr && e->Parent() != nullptr;
       e = e->Parent()->ToElement()) {
    if (e->Parent()->ToDocument() != nullptr) break;  // the <robot> root
    std::string part = e->Name();
    if (const char* name = e->Attribute("name")) part += " \"" + std::string(name) + "\"";
    if (const char* ref = e->Attribute("reference")) {
      part += " reference=\"" + std::string(ref) + "\"";
    }
    if (const char* joint = e->Attribute("joint")) {
      part += " joint=\"" + std::string(joint) + "\"";
    }
    path = path.empty() ? part : part + " > " + path;
  }
  return path;
}

std::string DescribeWithLine(const XMLElement* element) {
  return Describe(element) + " (line " + std::to_string(element->GetLineNum()) + ")";
}

[[noreturn]] void Fail(const XMLElement* element, const std::string& reason) {
  throw UrdfError("urdf: " + DescribeWithLine(element) + ": " + reason);
}

std::vector<std::string> Tokens(const char* text) {
  std::istringstream in(text);
  std::vector<std::string> tokens;
  for (std::string token; in >> token;) tokens.push_back(token);
  return tokens;
}

using Names = std::vector<std::string>;

std::string Join(const Names& names, const char* before, const char* after) {
  std::string list;
  for (const std::string& name : names) {
    if (!list.empty()) list += ", ";
    list += std::string(before) + name + after;
  }
  return list;
}

// Parses attribute `name` as `count` finite numbers; returns false when absent.
bool NumbersAttribute(const XMLElement* element, const char* name, std::size_t count,
                      std::vector<double>* values) {
  const char* text = element->Attribute(name);
  if (text == nullptr) return false;
  const std::vector<std::string> tokens = Tokens(text);
  const std::string quoted = std::string(name) + "=\"" + text + "\"";
  if (tokens.size() != count) {
    Fail(element, quoted + " has " + std::to_string(tokens.size()) + " numbers, expected " +
                      std::to_string(count));
  }
  values->resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!ParseFiniteNumber(tokens[i], &(*values)[i])) {
      Fail(element, quoted + ": \"" + tokens[i] + "\" is not a finite number");
    }
  }
  return true;
}

// "[low, high] unit" of an error line.
std::string Range(double low, double high, const char* unit) {
  return "[" + Format(low) + ", " + Format(high) + "]" + unit;
}

// Every one of `values` (of attribute `name`) in [low, high] (urdf_scene.h, "Bounds").
void RequireInRange(const XMLElement* element, const char* name,
                    const std::vector<double>& values, double low, double high, const char* unit,
                    const char* why = "") {
  for (double v : values) {
    if (v < low || v > high) {
      Fail(element, std::string(name) + "=\"" + element->Attribute(name) + "\": " + Format(v) +
                        " is out of range, expected " + Range(low, high, unit) + why);
    }
  }
}

// `count` numbers of attribute `name`, each > 0 (or ≥ 0 with allow_zero); the attribute is
// required.
std::vector<double> RequirePositive(const XMLElement* element, const char* name,
                                    std::size_t count, bool allow_zero = false) {
  std::vector<double> values;
  if (!NumbersAttribute(element, name, count, &values)) {
    Fail(element, std::string("attribute ") + name + " is missing");
  }
  for (double v : values) {
    if (!(v > 0.0 || (allow_zero && v == 0.0))) {
      Fail(element, std::string(name) + "=\"" + element->Attribute(name) + "\" must be " +
                        (allow_zero ? ">= 0" : "> 0"));
    }
  }
  return values;
}

// The numeric attributes urdfdom reads, by element name: checked wherever they occur in links and
// joints (visuals included: NaN anywhere is an error), with the bounds of urdf_scene.h: every
// origin within kMaxCoordinate, masses in [kMinMass, kMaxMass], and inside a <collision>
// (`in_collision`: what is simulated) sizes in [kMinLength, kMaxLength].
void CheckNumbers(const XMLElement* element, bool in_collision = false) {
  const std::string tag = element->Name();
  in_collision = in_collision || tag == "collision";
  std::vector<double> values;
  const auto size = [&](const char* name, std::size_t count) {
    const std::vector<double> sizes = RequirePositive(element, name, count);
    if (in_collision) RequireInRange(element, name, sizes, kMinLength, kMaxLength, " m");
  };
  if (tag == "origin") {
    if (NumbersAttribute(element, "xyz", 3, &values)) {
      RequireInRange(element, "xyz", values, -kMaxCoordinate, kMaxCoordinate, " m");
    }
    NumbersAttribute(element, "rpy", 3, &values);
  } else if (tag == "mass") {
    RequireInRange(element, "value", RequirePositive(element, "value", 1), kMinMass, kMaxMass,
                   " kg");
  } else if (tag == "inertia") {
    for (const char* name : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
      if (!NumbersAttribute(element, name, 1, &values)) {
        Fail(element, std::string("attribute ") + name + " is missing");
      }
    }
  } else if (tag == "sphere") {
    size("radius", 1);
  } else if (tag == "cylinder") {
    size("radius", 1);
    size("length", 1);
  } else if (tag == "box") {
    size("size", 3);
  } else if (tag == "mesh" || tag == "axis") {
    NumbersAttribute(element, tag == "mesh" ? "scale" : "xyz", 3, &values);
  } else if (tag == "color") {
    NumbersAttribute(element, "rgba", 4, &values);
  } else {
    for (const char* name : {"lower", "upper", "effort", "velocity", "damping", "friction",
                             "soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity",
                             "rising", "falling", "multiplier", "offset"}) {
      NumbersAttribute(element, name, 1, &values);
    }
  }
  if (tag == "inertial") {
    if (element->FirstChildElement("mass") == nullptr) Fail(element, "no <mass>");
    if (element->FirstChildElement("inertia") == nullptr) Fail(element, "no <inertia>");
  }
  for (const XMLElement* child = element->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    CheckNumbers(child, in_collision);
  }
}

// The text of `element` as one number in [low, high].
double TextNumber(const XMLElement* element, double low, double high, const char* range) {
  const std::string text = element->GetText() != nullptr ? element->GetText() : "";
  const std::vector<std::string> tokens = Tokens(text.c_str());
  double value = 0.0;
  if (tokens.size() != 1 || !ParseFiniteNumber(tokens[0], &value)) {
    Fail(element, "\"" + text + "\" is not a finite number");
  }
  if (value < low || value > high) {
    Fail(element, tokens[0] + " is out of range, expected " + range);
  }
  return value;
}

const XMLElement* Child(const XMLElement* element, std::initializer_list<const char*> path) {
  for (const char* name : path) {
    if (element == nullptr) return nullptr;
    element = element->FirstChildElement(name);
  }
  return element;
}

// <gazebo reference="link">: surface friction of the link's collisions.
void ReadGazebo(const XMLElement* gazebo, LinkSurface* surface, std::vector<std::string>* warnings) {
  const std::string friction_range = Range(0.0, kMaxFriction, "");
  const std::string radius_range = Range(0.0, kMaxLength, " m");
  const auto friction = [&](const XMLElement* e) {
    return TextNumber(e, 0.0, kMaxFriction, friction_range.c_str());
  };
  // legacy shortcut <mu1>, still common in URDFs written for Gazebo classic
  if (const XMLElement* mu1 = gazebo->FirstChildElement("mu1")) {
    surface->mu = friction(mu1);
  }
  // Bullet's rolling friction (a length: the rolling torque's bound per unit normal force)
  const auto rolling = [&](const XMLElement* e) {
    return TextNumber(e, 0.0, kMaxLength, radius_range.c_str());
  };
  if (const XMLElement* r = gazebo->FirstChildElement("rolling_friction")) {
    surface->rolling_friction = rolling(r);
  }
  for (const XMLElement* collision = gazebo->FirstChildElement("collision"); collision != nullptr;
       collision = collision->NextSiblingElement("collision")) {
    const XMLElement* friction_element = Child(collision, {"surface", "friction"});
    if (friction_element == nullptr) continue;
    if (const XMLElement* mu = Child(friction_element, {"ode", "mu"})) {
      surface->mu = friction(mu);
    }
    if (const XMLElement* r = Child(friction_element, {"bullet", "rolling_friction"})) {
      surface->rolling_friction = rolling(r);
    }
    if (const XMLElement* mu2 = Child(friction_element, {"ode", "mu2"})) {
      if (friction(mu2) != surface->mu) {
        warnings->push_back("urdf: " + Describe(mu2) +
                            ": anisotropic friction is not supported, using mu");
      }
    }
    if (const XMLElement* torsional = friction_element->FirstChildElement("torsional")) {
      if (const XMLElement* c = torsional->FirstChildElement("coefficient")) {
        surface->torsional_coefficient = friction(c);
      }
      if (const XMLElement* r = torsional->FirstChildElement("patch_radius")) {
        surface->patch_radius = TextNumber(r, 0.0, kMaxLength, radius_range.c_str());
      }
      if (const XMLElement* use = torsional->FirstChildElement("use_patch_radius")) {
        const char* text = use->GetText();
        if (text != nullptr && (std::string(text) == "false" || std::string(text) == "0")) {
          warnings->push_back("urdf: " + Describe(use) +
                              ": surface_radius torsional friction is not supported, "
                              "using patch_radius");
        }
      }
    }
  }
}

// Typos are errors: every attribute of `element` must be one of `allowed`.
void RequireOnlyAttributes(const XMLElement* element, const Names& allowed) {
  for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
    bool known = false;
    for (const std::string& name : allowed) known = known || a->Name() == name;
    if (!known) {
      Fail(element, "unknown attribute \"" + std::string(a->Name()) + "\"; allowed: " +
                        (allowed.size() == 0 ? std::string("none") : Join(allowed, "", "")));
    }
  }
}

void RequireNoChildren(const XMLElement* element) {
  if (const XMLElement* child = element->FirstChildElement()) {
    Fail(child, "unknown element <" + std::string(child->Name()) + ">; <" + element->Name() +
                    "> has no child elements");
  }
}

// <collision name="c"> inside <nonsmooth_sim>: exactly one shape URDF cannot express.
ShapeOverride ReadShapeOverride(const XMLElement* collision) {
  static const Names kShapes = {
      "ellipsoid semi_axes=\"a b c\"", "capsule radius=\"r\" length=\"l\"", "plane",
      "body_of_revolution axis=\"x y z\" tolerance=\"t\""};
  RequireOnlyAttributes(collision, {"name"});
  const char* name = collision->Attribute("name");
  if (name == nullptr || *name == '\0') {
    Fail(collision, "attribute name (the name of one of the link's <collision>s) is missing");
  }
  const XMLElement* element = collision->FirstChildElement();
  if (element == nullptr) {
    Fail(collision, "no shape; expected one of " + Join(kShapes, "<", "/>"));
  }
  if (const XMLElement* second = element->NextSiblingElement()) {
    Fail(second, "a second shape; expected exactly one of " + Join(kShapes, "<", "/>"));
  }
  RequireNoChildren(element);
  ShapeOverride result;
  result.where = DescribeWithLine(element);
  const std::string tag = element->Name();
  if (tag == "ellipsoid") {
    RequireOnlyAttributes(element, {"semi_axes"});
    const std::vector<double> axes = RequirePositive(element, "semi_axes", 3);
    RequireInRange(element, "semi_axes", axes, kMinLength, kMaxLength, " m");
    result.shape = Shape::Ellipsoid(Eigen::Vector3d(axes[0], axes[1], axes[2]));
  } else if (tag == "capsule") {
    RequireOnlyAttributes(element, {"radius", "length"});
    const double radius = RequirePositive(element, "radius", 1)[0];
    RequireInRange(element, "radius", {radius}, kMinLength, kMaxLength, " m");
    // length of the segment between the centres of the end caps (0: a sphere)
    const double length = RequirePositive(element, "length", 1, /*allow_zero=*/true)[0];
    RequireInRange(element, "length", {length}, 0.0, kMaxLength, " m");
    result.shape = Shape::Capsule(radius, 0.5 * length);
  } else if (tag == "plane") {
    RequireOnlyAttributes(element, {});
    result.shape = Shape::Plane();
  } else if (tag == "body_of_revolution") {
    // of the collision's <mesh>: axis (default 0 0 1) and tolerance [m] (default 1 % of its size)
    RequireOnlyAttributes(element, {"axis", "tolerance"});
    RevolutionRequest request;
    std::vector<double> values;
    if (NumbersAttribute(element, "axis", 3, &values)) {
      request.axis = Eigen::Vector3d(values[0], values[1], values[2]);
      if (!(request.axis.norm() > 0.0)) {
        Fail(element, "axis=\"" + std::string(element->Attribute("axis")) +
                          "\" is not a direction; expected three numbers, not all 0");
      }
    }
    if (element->Attribute("tolerance") != nullptr) {
      const double tolerance = RequirePositive(element, "tolerance", 1)[0];
      RequireInRange(element, "tolerance", {tolerance}, kMinLength, kMaxLength, " m");
      request.tolerance = tolerance;
    }
    result.revolution = request;
  } else {
    Fail(element, "unknown shape <" + tag + ">; allowed: " + Join(kShapes, "<", "/>") +
                      " (sphere, box and cylinder: use the URDF <geometry>)");
  }
  return result;
}

// <nonsmooth_sim joint="j">: exactly one <hold/> or <hold position="q"/>, one per joint in the file
// (the joint, its type and q's range are checked against the model: link_groups.h).
void ReadJointBlock(const XMLElement* block, UrdfXml* result) {
  static const char* kAllowed =
      "<hold/> or <hold position=\"q\"/> (q in rad for revolute and continuous joints, in m "
      "for prismatic ones; default 0)";
  const std::string joint = block->Attribute("joint");
  if (block->Attribute("reference") != nullptr) {
    Fail(block, "attributes reference and joint in one block; a block is about one link "
                "(reference=\"link\") or one joint (joint=\"joint\")");
  }
  if (joint.empty()) Fail(block, "attribute joint is empty; expected the name of a joint");
  const XMLElement* hold = nullptr;
  for (const XMLElement* e = block->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    if (std::string(e->Name()) != "hold") {
      Fail(e, "unknown element <" + std::string(e->Name()) +
                  ">; allowed in <nonsmooth_sim joint=\"...\">: " + kAllowed);
    }
    if (hold != nullptr) Fail(e, "<hold> given twice in one block");
    hold = e;
  }
  if (hold == nullptr) Fail(block, std::string("no <hold>; expected ") + kAllowed);
  RequireOnlyAttributes(hold, {"position"});
  RequireNoChildren(hold);
  JointHold result_hold;
  result_hold.joint = joint;
  result_hold.where = DescribeWithLine(hold);
  result_hold.line = block->GetLineNum();
  std::vector<double> values;
  if (NumbersAttribute(hold, "position", 1, &values)) result_hold.position = values[0];
  for (const JointHold& other : result->joint_holds) {
    if (other.joint == joint) {
      Fail(hold, "joint \"" + joint + "\" is already held by " + other.where +
                     " (one <hold> per joint)");
    }
  }
  result->joint_holds.push_back(std::move(result_hold));
}

// <nonsmooth_sim reference="link">: restitution, friction set, rolling resistance and shape
// overrides of one link; <nonsmooth_sim joint="j">: a joint held rigid (ReadJointBlock).
void ReadNonsmoothSim(const XMLElement* block, UrdfXml* result) {
  static const Names kElements = {
      "restitution", "friction_set", "rolling_resistance", "collision name=\"...\""};
  RequireOnlyAttributes(block, {"reference", "joint"});
  if (block->Attribute("joint") != nullptr) {
    ReadJointBlock(block, result);
    return;
  }
  const char* ref = block->Attribute("reference");
  if (ref == nullptr) {
    Fail(block, "attribute reference (a link name) or joint (a joint name) is missing");
  }
  result->extension_blocks.push_back({ref, DescribeWithLine(block)});
  LinkSurface& surface = result->surfaces[ref];
  bool has_restitution = false;
  bool has_friction_set = false;
  bool has_rolling_resistance = false;
  for (const XMLElement* e = block->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "restitution" || tag == "friction_set" || tag == "rolling_resistance") {
      RequireOnlyAttributes(e, {});
      RequireNoChildren(e);
      bool& seen = tag == "restitution"    ? has_restitution
                   : tag == "friction_set" ? has_friction_set
                                           : has_rolling_resistance;
      if (seen) Fail(e, "<" + tag + "> given twice in one block");
      seen = true;
    }
    if (tag == "restitution") {
      surface.restitution = TextNumber(e, 0.0, 1.0, "[0, 1]");
    } else if (tag == "rolling_resistance") {
      surface.rolling_resistance =
          TextNumber(e, 0.0, kMaxLength, Range(0.0, kMaxLength, " m").c_str());
    } else if (tag == "friction_set") {
      const std::vector<std::string> tokens = Tokens(e->GetText() != nullptr ? e->GetText() : "");
      const std::optional<FrictionSet> set =
          tokens.size() == 1 ? FrictionSetFromName(tokens[0]) : std::nullopt;
      if (!set) {
        Fail(e, "\"" + std::string(e->GetText() != nullptr ? e->GetText() : "") +
                    "\" is not a friction set; allowed: " + FrictionSetNameList());
      }
      surface.friction_set = *set;
    } else if (tag == "collision") {
      const ShapeOverride shape = ReadShapeOverride(e);
      const auto [it, inserted] =
          result->shapes[ref].emplace(e->Attribute("name"), shape);
      if (!inserted) {
        Fail(e, "a shape for this collision is already given at " + it->second.where);
      }
    } else {
      Fail(e, "unknown element <" + tag + ">; allowed in <nonsmooth_sim>: " +
                  Join(kElements, "<", ">"));
    }
  }
}

// XML 1.0 text is UTF-8 without control characters other than tab, newline and carriage return
// (the Char production); TinyXML2 does not check it. Names with such bytes loaded before, could not
// be written as YAML or read back (initial_state.h), and reached TF and topic names.
void CheckXmlCharacters(const std::string& xml) {
  int line = 1;
  const auto fail = [&line](unsigned char byte, const char* reason) {
    static constexpr char kHex[] = "0123456789abcdef";
    throw UrdfError("urdf: not well-formed XML: line " + std::to_string(line) + ": byte 0x" +
                    kHex[byte >> 4] + kHex[byte & 0xf] + " " + reason);
  };
  const auto byte_at = [&xml](std::size_t i) { return static_cast<unsigned char>(xml[i]); };
  for (std::size_t i = 0; i < xml.size();) {
    const unsigned char c = byte_at(i);
    if (c < 0x80) {
      if (c == '\n') ++line;
      if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') {
        fail(c, "is a control character, not allowed in XML");
      }
      ++i;
      continue;
    }
    // the length of the sequence and the range of its second byte (no overlong forms, no
    // surrogates, nothing above U+10FFFF: RFC 3629)
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xbf;
    if (c >= 0xc2 && c <= 0xdf) {
      length = 2;
    } else if (c >= 0xe0 && c <= 0xef) {
      length = 3;
      if (c == 0xe0) low = 0xa0;
      if (c == 0xed) high = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
      length = 4;
      if (c == 0xf0) low = 0x90;
      if (c == 0xf4) high = 0x8f;
    } else {
      fail(c, "is not valid UTF-8");
    }
    for (std::size_t k = 1; k < length; ++k) {
      const unsigned char next = i + k < xml.size() ? byte_at(i + k) : 0;
      const bool ok = k == 1 ? next >= low && next <= high : next >= 0x80 && next <= 0xbf;
      if (!ok) fail(c, "starts a UTF-8 sequence that is not valid");
    }
    i += length;
  }
}

// The bounds of bounded_input.h on names (robot, links, joints, collisions) and on the number of
// collisions, before urdfdom builds the model.
void CheckSizes(const XMLElement* robot) {
  const auto name_of = [](const XMLElement* e, const std::string& what) {
    if (const char* name = e->Attribute("name")) {
      try {
        CheckNameLength(what, name);
      } catch (const std::invalid_argument& error) {
        throw UrdfError("urdf: line " + std::to_string(e->GetLineNum()) + ": " + error.what());
      }
    }
  };
  name_of(robot, "robot");
  std::size_t collisions = 0;
  for (const XMLElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag != "link" && tag != "joint") continue;
    name_of(e, tag);
    if (tag != "link") continue;
    for (const XMLElement* c = e->FirstChildElement("collision"); c != nullptr;
         c = c->NextSiblingElement("collision")) {
      name_of(c, "collision");
      if (++collisions > kMaxCollisionsPerModel) {
        throw UrdfError("urdf: " + DescribeWithLine(c) + ": more than " +
                        std::to_string(kMaxCollisionsPerModel) +
                        " collisions in one URDF (the bound on collisions per model)");
      }
    }
  }
}

}  // namespace

bool ParseFiniteNumber(std::string_view text, double* value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(*value);
}

UrdfXml ParseUrdfXml(const std::string& xml) {
  CheckXmlCharacters(xml);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw UrdfError(std::string("urdf: not well-formed XML: ") + doc.ErrorStr());
  }
  const XMLElement* robot = doc.RootElement();
  if (robot == nullptr) throw UrdfError("urdf: no XML element (empty document)");
  if (std::string(robot->Name()) != "robot") {
    throw UrdfError("urdf: the root element is <" + std::string(robot->Name()) +
                    ">, expected <robot> (line " + std::to_string(robot->GetLineNum()) + ")");
  }
  CheckSizes(robot);
  UrdfXml result;
  for (const XMLElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "link" || tag == "joint") CheckNumbers(e);
    if (tag == "link" && e->Attribute("name") != nullptr) {
      result.link_order.push_back(e->Attribute("name"));
    }
  }
  // extension tags, by link name (several blocks for one link merge, later ones win)
  for (const XMLElement* e = robot->FirstChildElement("gazebo"); e != nullptr;
       e = e->NextSiblingElement("gazebo")) {
    if (const char* ref = e->Attribute("reference")) {
      result.gazebo_references.push_back(ref);
      ReadGazebo(e, &result.surfaces[ref], &result.warnings);
    }
  }
  for (const XMLElement* e = robot->FirstChildElement("nonsmooth_sim"); e != nullptr;
       e = e->NextSiblingElement("nonsmooth_sim")) {
    ReadNonsmoothSim(e, &result);
  }
  return result;
}

}  // namespace nonsmooth_sim::scene_io
