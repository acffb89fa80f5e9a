// Initial state from YAML (yaml-cpp). See initial_state.h.
#include "nonsmooth_sim/scene_io/initial_state.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/format.h"
#include "nonsmooth_sim/scene_io/urdf_xml.h"

namespace nonsmooth_sim::scene_io {
namespace {

constexpr const char* kBodyKeys = "position, orientation, linear_velocity, angular_velocity";

// A key of the body map: its name, its length and what it means, for error lines.
struct Key {
  const char* name;
  int size;
  const char* meaning;
};
constexpr Key kKeys[] = {
    {"position", 3, "[x, y, z]: origin of the link frame in the world [m]"},
    {"orientation", 4, "[qx, qy, qz, qw]: link axes to world, non-zero"},
    {"linear_velocity", 3, "[vx, vy, vz]: velocity of the centre of mass, world axes [m/s]"},
    {"angular_velocity", 3, "[wx, wy, wz]: angular velocity in the link axes [rad/s]"},
};

int Line(const YAML::Node& node) { return node.Mark().line + 1; }

// The bound of key `name` on `value` (initial_state.h); throws std::invalid_argument "<reason>".
void CheckKey(const std::string& name, const Eigen::Vector3d& value) {
  if (name == "position") {
    CheckInitialPosition(name, value);
  } else if (name == "linear_velocity") {
    CheckInitialLinearVelocity(name, value);
  } else if (name == "angular_velocity") {
    CheckInitialAngularVelocity(name, value);
  }
}

// The reason of CheckKey without its leading "<name>: ".
std::string BoundViolation(const std::string& name, const Eigen::Vector3d& value) {
  try {
    CheckKey(name, value);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    return what.substr(std::min(what.size(), name.size() + 2));
  }
  return "";
}

[[noreturn]] void Fail(const std::string& path, int line, const std::string& reason) {
  throw InitialStateError("initial state: " + path +
                          (line > 0 ? " (line " + std::to_string(line) + ")" : "") + ": " + reason);
}

std::string ScalarOr(const YAML::Node& node, const std::string& fallback) {
  return node.IsScalar() ? node.Scalar() : fallback;
}

// `key.size` finite numbers from a flow or block sequence.
Eigen::VectorXd Numbers(const YAML::Node& node, const std::string& path, const Key& key) {
  const std::string expected = "expected " + std::string(key.meaning);
  if (!node.IsSequence()) Fail(path, Line(node), "not a list; " + expected);
  if (static_cast<int>(node.size()) != key.size) {
    Fail(path, Line(node),
         "has " + std::to_string(node.size()) + " numbers; " + expected);
  }
  Eigen::VectorXd values(key.size);
  for (int i = 0; i < key.size; ++i) {
    const YAML::Node item = node[i];
    double value = 0.0;
    if (!item.IsScalar() || !ParseFiniteNumber(item.Scalar(), &value)) {
      Fail(path + "[" + std::to_string(i) + "]", Line(item),
           "\"" + ScalarOr(item, "(not a number)") + "\" is not a finite number; " + expected);
    }
    values[i] = value;
  }
  return values;
}

BodyInitialState ParseBody(const YAML::Node& node, const std::string& path, int line) {
  BodyInitialState body;
  body.line = line;
  if (node.IsNull()) return body;  // "tippe_top:" alone: the defaults
  if (!node.IsMap()) Fail(path, Line(node), "not a map; allowed keys: " + std::string(kBodyKeys));
  std::map<std::string, int> seen;  // key → line
  for (const auto& entry : node) {
    const std::string name = ScalarOr(entry.first, "(not a name)");
    const std::string key_path = path + "." + name;
    const Key* key = nullptr;
    for (const Key& k : kKeys) {
      if (name == k.name) key = &k;
    }
    if (key == nullptr) {
      Fail(key_path, Line(entry.first), "unknown key; allowed: " + std::string(kBodyKeys));
    }
    if (const auto [it, inserted] = seen.emplace(name, Line(entry.first)); !inserted) {
      Fail(key_path, Line(entry.first), "given twice (also on line " +
                                            std::to_string(it->second) + ")");
    }
    const Eigen::VectorXd v = Numbers(entry.second, key_path, *key);
    if (key->size == 3) {
      const std::string violation = BoundViolation(name, v.head<3>());
      if (!violation.empty()) Fail(key_path, Line(entry.second), violation);
    }
    if (key == &kKeys[0]) {
      body.position = v.head<3>();
    } else if (key == &kKeys[1]) {
      const Eigen::Quaterniond q(v[3], v[0], v[1], v[2]);  // (w, x, y, z) from [qx, qy, qz, qw]
      if (!(q.coeffs().squaredNorm() > 0.0)) {
        Fail(key_path, Line(entry.second),
             "the zero quaternion is not a rotation; expected " + std::string(key->meaning));
      }
      // finite components whose |q|² overflows (1e200) would normalise to the zero quaternion
      if (!std::isfinite(q.coeffs().squaredNorm())) {
        Fail(key_path, Line(entry.second),
             "|q| is too large to normalise (|q|^2 overflows); expected a unit quaternion, " +
                 std::string(key->meaning));
      }
      body.orientation = q.normalized();
    } else if (key == &kKeys[2]) {
      body.linear_velocity = v.head<3>();
    } else {
      body.angular_velocity = v.head<3>();
    }
  }
  return body;
}

std::string ReadFile(const std::string& path) {
  try {
    return ReadBoundedFile(path, kMaxInputBytes, "a YAML file");
  } catch (const std::invalid_argument& e) {
    throw InitialStateError("initial state: " + path + ": " + e.what());
  }
}

}  // namespace

void CheckInitialPosition(const std::string& what, const Eigen::Vector3d& position) {
  if (!(position.cwiseAbs().maxCoeff() <= kMaxInitialCoordinate) || !position.allFinite()) {
    throw std::invalid_argument(what + ": (" + Format(position.x()) + ", " + Format(position.y()) +
                                ", " + Format(position.z()) + ") m: every coordinate must be in [" +
                                Format(-kMaxInitialCoordinate) + ", " +
                                Format(kMaxInitialCoordinate) + "] m");
  }
}

void CheckInitialLinearVelocity(const std::string& what, const Eigen::Vector3d& velocity) {
  const double speed = velocity.stableNorm();  // norm() overflows for 1e300
  if (!(speed <= kMaxInitialSpeed)) {
    throw std::invalid_argument(what + ": |v| = " + Format(speed) + " m/s must be <= " +
                                Format(kMaxInitialSpeed) + " m/s");
  }
}

void CheckInitialAngularVelocity(const std::string& what, const Eigen::Vector3d& velocity) {
  const double speed = velocity.stableNorm();  // norm() overflows for 1e300
  if (!(speed <= kMaxInitialAngularSpeed)) {
    throw std::invalid_argument(what + ": |w| = " + Format(speed) + " rad/s must be <= " +
                                Format(kMaxInitialAngularSpeed) +
                                " rad/s (finite kinetic energy, bounded dt*|w|)");
  }
}

InitialStateSpec ParseInitialStateYaml(const std::string& yaml_text) {
  // the bounds before yaml-cpp allocates anything (bounded_input.h)
  const YAML::Node root = [&] {
    try {
      return LoadOneYamlDocument(yaml_text);
    } catch (const YamlTextError& e) {
      throw InitialStateError("initial state (line " + std::to_string(e.line) + ", column " +
                              std::to_string(e.column) + "): " + e.what());
    } catch (const std::invalid_argument& e) {
      throw InitialStateError(std::string("initial state: ") + e.what());
    }
  }();
  InitialStateSpec spec;
  if (root.IsNull()) return spec;  // an empty document
  if (!root.IsMap()) {
    Fail("the document", Line(root), "not a map; expected the key bodies: {<link>: {...}}");
  }
  std::optional<YAML::Node> found;
  int bodies_line = 0;
  for (const auto& entry : root) {
    const std::string name = ScalarOr(entry.first, "(not a name)");
    if (name != "bodies") Fail(name, Line(entry.first), "unknown key; allowed: bodies");
    if (found) {
      Fail(name, Line(entry.first), "given twice (also on line " + std::to_string(bodies_line) +
                                        ")");
    }
    found.emplace(entry.second);
    bodies_line = Line(entry.first);
  }
  if (!found || found->IsNull()) return spec;  // "{}" or "bodies:" alone
  const YAML::Node& bodies = *found;
  if (!bodies.IsMap()) {
    Fail("bodies", Line(bodies), "not a map; expected {<link>: {" + std::string(kBodyKeys) + "}}");
  }
  for (const auto& entry : bodies) {
    const std::string path = "bodies." + ScalarOr(entry.first, "(not a name)");
    if (!entry.first.IsScalar()) Fail(path, Line(entry.first), "a body key must be a link name");
    const std::string& link = entry.first.Scalar();
    if (const auto it = spec.find(link); it != spec.end()) {
      Fail(path, Line(entry.first), "given twice (also on line " + std::to_string(it->second.line) +
                                        ")");
    }
    spec.emplace(link, ParseBody(entry.second, path, Line(entry.first)));
  }
  return spec;
}

std::vector<BodyState> ApplyInitialState(const Scene& scene,
                                         const std::vector<BodyState>& defaults,
                                         const InitialStateSpec& spec) {
  ValidateState(scene, defaults);
  std::vector<BodyState> state = defaults;
  for (const auto& [link, start] : spec) {
    int index = -1;
    for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
      if (scene.bodies[b].name == link) index = b;
    }
    if (index < 0) {
      std::string bodies;
      for (const RigidBody& body : scene.bodies) {
        bodies += (bodies.empty() ? "\"" : ", \"") + body.name + "\"";
      }
      Fail("bodies." + link, start.line,
           "not a free body of the scene (static links and links fixed to a body have no state of "
           "their own); bodies: " + bodies);
    }
    // a spec built in code (the node's parameters) gets the bounds the YAML parser checks
    const std::string path = "bodies." + link;
    const std::pair<const char*, const std::optional<Eigen::Vector3d>*> parts[] = {
        {"position", &start.position},
        {"linear_velocity", &start.linear_velocity},
        {"angular_velocity", &start.angular_velocity}};
    for (const auto& [name, part] : parts) {
      if (!*part) continue;
      const std::string violation = BoundViolation(name, **part);
      if (!violation.empty()) Fail(path + "." + name, start.line, violation);
    }
    const Eigen::Vector3d& c = scene.bodies[index].com_in_link;
    BodyState& s = state[index];
    // the link frame's pose: position = r_S − R c
    const Eigen::Quaterniond old_rotation = s.orientation.normalized();
    const Eigen::Vector3d link_position = start.position.value_or(s.position - old_rotation * c);
    const Eigen::Quaterniond rotation = start.orientation.value_or(old_rotation);
    if (start.position || start.orientation) {
      s.orientation = rotation;
      s.position = link_position + rotation * c;  // r_S = position + R c
      const std::string violation = BoundViolation("position", s.position);
      if (!violation.empty()) {
        Fail(path + ".position", start.line, "the centre of mass " + violation);
      }
    }
    if (start.linear_velocity) s.linear_velocity = *start.linear_velocity;
    if (start.angular_velocity) s.angular_velocity = *start.angular_velocity;
  }
  return state;
}

std::vector<BodyState> InitialStateFromYaml(const Scene& scene, const std::string& yaml_text) {
  return ApplyInitialState(scene, scene.initial_state, ParseInitialStateYaml(yaml_text));
}

std::vector<BodyState> InitialStateFromYamlFile(const Scene& scene, const std::string& path) {
  const std::string text = ReadFile(path);
  try {
    return InitialStateFromYaml(scene, text);
  } catch (const InitialStateError& e) {
    // "initial state: <reason>" → "initial state: <path>: <reason>"
    const std::string what = e.what();
    const std::string prefix = "initial state";
    throw InitialStateError(prefix + ": " + path +
                            (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
  }
}

std::string InitialStateToYaml(const Scene& scene, const std::vector<BodyState>& state) {
  ValidateState(scene, state);
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  const auto list = [&out](const auto& values) {
    out << YAML::Flow << YAML::BeginSeq;
    for (int i = 0; i < values.size(); ++i) out << values[i];
    out << YAML::EndSeq;
  };
  out << YAML::BeginMap << YAML::Key << "bodies" << YAML::Value << YAML::BeginMap;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodyState& s = state[b];
    const Eigen::Quaterniond rotation = s.orientation.normalized();
    out << YAML::Key << scene.bodies[b].name << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "position" << YAML::Value;
    list(Eigen::Vector3d(s.position - rotation * scene.bodies[b].com_in_link));
    out << YAML::Key << "orientation" << YAML::Value;
    list(Eigen::Vector4d(rotation.coeffs()));  // Eigen's coeffs() are (x, y, z, w)
    out << YAML::Key << "linear_velocity" << YAML::Value;
    list(s.linear_velocity);
    out << YAML::Key << "angular_velocity" << YAML::Value;
    list(s.angular_velocity);
    out << YAML::EndMap;
  }
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace nonsmooth_sim::scene_io
