// A scripted schedule of world events from YAML. See schedule.h.
#include "nonsmooth_sim/scene_io/schedule.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/one_line.h"

namespace nonsmooth_sim::scene_io {
namespace {

[[noreturn]] void Fail(const YAML::Node& node, const std::string& what) {
  throw std::invalid_argument("line " + std::to_string(node.Mark().line + 1) + ": " + what);
}

double Number(const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) Fail(node, what + ": expected a number");
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    Fail(node, what + ": expected a number, got \"" + node.Scalar().substr(0, 40) + "\"");
  }
  if (!std::isfinite(value)) Fail(node, what + ": must be finite");
  return value;
}

std::string Name(const YAML::Node& node, const std::string& what) {
  if (!node || !node.IsScalar()) Fail(node, what + ": expected a name");
  CheckNameLength(what, node.Scalar());
  return node.Scalar();
}

template <int N>
Eigen::Matrix<double, N, 1> Vector(const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence() || node.size() != static_cast<std::size_t>(N)) {
    Fail(node, what + ": expected a list of " + std::to_string(N) + " numbers");
  }
  Eigen::Matrix<double, N, 1> v;
  for (int k = 0; k < N; ++k) v[k] = Number(node[static_cast<std::size_t>(k)], what);
  return v;
}

Eigen::Quaterniond Orientation(const YAML::Node& node, const std::string& what) {
  const Eigen::Vector4d q = Vector<4>(node, what + " [qx, qy, qz, qw]");
  return Eigen::Quaterniond(q[3], q[0], q[1], q[2]);  // checked and normalised by the world
}

// The keys of `map`, each one of `allowed` (comma-separated in the message).
void CheckKeys(const YAML::Node& map, const std::string& what,
               const std::vector<std::string>& allowed) {
  if (!map.IsMap()) Fail(map, what + ": expected a map");
  for (const auto& entry : map) {
    const std::string key = entry.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    Fail(entry.first, what + ": unknown key \"" + key.substr(0, 40) + "\"; allowed: " + list);
  }
}

ScheduledEvent Event(const YAML::Node& node, const std::string& folder) {
  CheckKeys(node, "event", {"at", "spawn", "wrench", "set_state", "delete"});
  ScheduledEvent event;
  event.line = node.Mark().line + 1;
  if (!node["at"]) Fail(node, "event: no \"at\" (its time [s])");
  event.time = Number(node["at"], "at");
  if (event.time < 0.0) Fail(node["at"], "at: must be >= 0 s");
  if (node.size() != 2) {
    Fail(node, "event: expected \"at\" and one of spawn, wrench, set_state, delete");
  }
  if (const YAML::Node n = node["spawn"]) {
    CheckKeys(n, "spawn", {"model", "urdf", "position", "orientation"});
    SpawnEvent e;
    e.model = Name(n["model"], "spawn: model");
    const std::string urdf = Name(n["urdf"], "spawn: urdf");
    e.urdf_path = urdf.front() == '/' || folder.empty() ? urdf : folder + "/" + urdf;
    if (n["position"]) e.position = Vector<3>(n["position"], "spawn: position");
    if (n["orientation"]) e.orientation = Orientation(n["orientation"], "spawn: orientation");
    event.what = e;
  } else if (const YAML::Node n = node["wrench"]) {
    CheckKeys(n, "wrench", {"body", "force", "torque", "point", "duration"});
    WrenchEvent e;
    e.body = Name(n["body"], "wrench: body");
    if (n["force"]) e.force = Vector<3>(n["force"], "wrench: force");
    if (n["torque"]) e.torque = Vector<3>(n["torque"], "wrench: torque");
    if (n["point"]) e.point = Vector<3>(n["point"], "wrench: point");
    if (!n["duration"]) Fail(n, "wrench: no duration [s] (< 0: until the end)");
    e.duration = Number(n["duration"], "wrench: duration");
    event.what = e;
  } else if (const YAML::Node n = node["set_state"]) {
    CheckKeys(n, "set_state",
              {"model", "position", "orientation", "linear_velocity", "angular_velocity"});
    StateEvent e;
    e.model = Name(n["model"], "set_state: model");
    if (n["position"]) e.position = Vector<3>(n["position"], "set_state: position");
    if (n["orientation"]) e.orientation = Orientation(n["orientation"], "set_state: orientation");
    if (n["linear_velocity"]) {
      e.linear_velocity = Vector<3>(n["linear_velocity"], "set_state: linear_velocity");
    }
    if (n["angular_velocity"]) {
      e.angular_velocity = Vector<3>(n["angular_velocity"], "set_state: angular_velocity");
    }
    event.what = e;
  } else {
    const YAML::Node d = node["delete"];
    CheckKeys(d, "delete", {"model"});
    event.what = DeleteEvent{Name(d["model"], "delete: model")};
  }
  return event;
}

}  // namespace

std::vector<ScheduledEvent> ParseScheduleYaml(const std::string& text, const std::string& folder) {
  const YAML::Node root = [&] {
    try {
      return LoadOneYamlDocument(text);  // bounded: size, nesting, one document (bounded_input.h)
    } catch (const YamlTextError& e) {
      throw std::invalid_argument("line " + std::to_string(e.line) + ", column " +
                                  std::to_string(e.column) + ": " + OneLine(e.what()));
    }
  }();
  if (!root.IsMap() || !root["events"] || root.size() != 1) {
    throw std::invalid_argument("expected a map with the one key events (a list of events)");
  }
  const YAML::Node events = root["events"];
  if (!events.IsSequence()) Fail(events, "events: expected a list");
  if (events.size() > kMaxScheduleEvents) {
    Fail(events, "events: " + std::to_string(events.size()) + " events, more than the bound " +
                     std::to_string(kMaxScheduleEvents));
  }
  std::vector<ScheduledEvent> schedule;
  for (const YAML::Node& node : events) schedule.push_back(Event(node, folder));
  std::stable_sort(schedule.begin(), schedule.end(),
                   [](const ScheduledEvent& a, const ScheduledEvent& b) { return a.time < b.time; });
  return schedule;
}

std::vector<ScheduledEvent> LoadScheduleFile(const std::string& path) {
  try {
    const std::string text = ReadBoundedFile(path, kMaxInputBytes, "a schedule YAML file");
    const std::size_t slash = path.rfind('/');
    return ParseScheduleYaml(text, slash == std::string::npos ? "." : path.substr(0, slash));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

}  // namespace nonsmooth_sim::scene_io
