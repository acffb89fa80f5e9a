// Private parameters of the node: read once, validated. See node_parameters.h.
#include "nonsmooth_sim/node/node_parameters.h"

#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/world/model_registry.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace nonsmooth_sim::node {
namespace {

class ParameterReader {
 public:
  explicit ParameterReader(const ros::NodeHandle& nh) : nh_(nh) {}

  [[noreturn]] void Fail(const std::string& name, const std::string& reason) const {
    throw std::invalid_argument("parameter ~" + name + ": " + reason);
  }

  bool Get(const std::string& name, XmlRpc::XmlRpcValue* value) const {
    return nh_.hasParam(name) && nh_.getParam(name, *value);
  }

  static bool IsNumber(XmlRpc::XmlRpcValue& v) {
    return v.getType() == XmlRpc::XmlRpcValue::TypeDouble ||
           v.getType() == XmlRpc::XmlRpcValue::TypeInt;
  }
  static double AsNumber(XmlRpc::XmlRpcValue& v) {
    return v.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<int>(v)
                                                       : static_cast<double>(v);
  }

  std::optional<double> Number(const std::string& name) const {
    XmlRpc::XmlRpcValue v;
    if (!Get(name, &v)) return std::nullopt;
    if (!IsNumber(v)) Fail(name, "expected a number");
    const double x = AsNumber(v);
    if (!std::isfinite(x)) Fail(name, "must be finite");
    return x;
  }
  void Number(const std::string& name, double* value) const {
    if (auto x = Number(name)) *value = *x;
  }
  void Integer(const std::string& name, int* value) const {
    XmlRpc::XmlRpcValue v;
    if (!Get(name, &v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) Fail(name, "expected an integer");
    *value = static_cast<int>(v);
  }
  void Bool(const std::string& name, bool* value) const {
    XmlRpc::XmlRpcValue v;
    if (!Get(name, &v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) Fail(name, "expected true or false");
    *value = static_cast<bool>(v);
  }
  void String(const std::string& name, std::string* value) const {
    XmlRpc::XmlRpcValue v;
    if (!Get(name, &v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) Fail(name, "expected a string");
    *value = static_cast<std::string>(v);
  }
  // A list of strings, or one string as a list of one (roscpp reads a command line's
  // _name:=value as a string, never as a list).
  void Strings(const std::string& name, std::vector<std::string>* values) const {
    XmlRpc::XmlRpcValue v;
    if (!Get(name, &v)) return;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
      values->push_back(static_cast<std::string>(v));
      return;
    }
    const char* expected = "expected a list of strings, or one string";
    if (v.getType() != XmlRpc::XmlRpcValue::TypeArray) Fail(name, expected);
    for (int i = 0; i < v.size(); ++i) {
      if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString) Fail(name, expected);
      values->push_back(static_cast<std::string>(v[i]));
    }
  }
  std::optional<Eigen::VectorXd> Numbers(const std::string& name, int count) const {
    XmlRpc::XmlRpcValue v;
    if (!Get(name, &v)) return std::nullopt;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || v.size() != count) {
      Fail(name, "expected a list of " + std::to_string(count) + " numbers");
    }
    Eigen::VectorXd x(count);
    for (int i = 0; i < count; ++i) {
      if (!IsNumber(v[i])) Fail(name, "expected a list of " + std::to_string(count) + " numbers");
      x[i] = AsNumber(v[i]);
    }
    if (!x.allFinite()) Fail(name, "must be finite");
    return x;
  }

 private:
  const ros::NodeHandle& nh_;
};

// ~initial_state: the YAML initial-state file loaded as parameters (rosparam load FILE
// ~initial_state): bodies/<link>/{position, orientation, linear_velocity, angular_velocity}.
scene_io::InitialStateSpec ReadInitialState(const ParameterReader& r) {
  scene_io::InitialStateSpec spec;
  XmlRpc::XmlRpcValue root;
  if (!r.Get("initial_state", &root)) return spec;
  if (root.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    r.Fail("initial_state", "expected a map with the key bodies");
  }
  for (auto& [key, value] : root) {
    if (key != "bodies") r.Fail("initial_state/" + key, "unknown key, expected bodies");
    if (value.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      r.Fail("initial_state/bodies", "expected a map from link names to states");
    }
    // bounded as the world: at most one entry per body it can hold, names as in a URDF
    if (static_cast<std::size_t>(value.size()) > world::ModelRegistry::kMaxWorldBodies) {
      r.Fail("initial_state/bodies",
             std::to_string(value.size()) + " entries, more than the bound of " +
                 std::to_string(world::ModelRegistry::kMaxWorldBodies) +
                 " (the most bodies a world holds)");
    }
    for (auto& [link, body] : value) {
      try {
        scene_io::CheckNameLength("link", link);
      } catch (const std::invalid_argument& e) {
        r.Fail("initial_state/bodies", e.what());
      }
      const std::string where = "initial_state/bodies/" + link;
      if (body.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
        r.Fail(where, "expected a map with position, orientation, linear_velocity, "
                      "angular_velocity");
      }
      scene_io::BodyInitialState& state = spec[link];
      for (auto& [field, unused] : body) {
        (void)unused;
        if (field == "position") {
          state.position = Eigen::Vector3d(*r.Numbers(where + "/position", 3));
        } else if (field == "orientation") {
          const Eigen::VectorXd q = *r.Numbers(where + "/orientation", 4);
          if (q.squaredNorm() == 0.0) r.Fail(where + "/orientation", "must not be zero");
          state.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
        } else if (field == "linear_velocity") {
          state.linear_velocity = Eigen::Vector3d(*r.Numbers(where + "/linear_velocity", 3));
        } else if (field == "angular_velocity") {
          state.angular_velocity = Eigen::Vector3d(*r.Numbers(where + "/angular_velocity", 3));
        } else {
          r.Fail(where + "/" + field,
                 "unknown key, expected position, orientation, linear_velocity, "
                 "angular_velocity");
        }
      }
    }
  }
  return spec;
}

void RequireRate(const char* name, double rate, bool zero_allowed) {
  if (!(rate > 0.0 || (zero_allowed && rate == 0.0))) {
    throw std::invalid_argument(std::string("parameter ~") + name + ": must be " +
                                (zero_allowed ? ">= 0 (0 = off)" : "> 0") + " [Hz], got " +
                                std::to_string(rate));
  }
}

std::string ReadFile(const std::string& path, std::size_t max_bytes) {
  try {
    return scene_io::ReadBoundedFile(path, max_bytes, "a URDF file");
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("parameter ~urdf_file: \"" + path + "\": " + e.what());
  }
}

}  // namespace

void ValidateNodeParameters(const NodeParameters& p) {
  if (p.world_frame.empty()) throw std::invalid_argument("parameter ~world_frame: empty");
  try {
    ValidateUrdfSceneOptions(p.scene);
    ValidateSimulatorOptions(p.simulator);
    ValidateInitialConditions(p.initial);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("parameters: ") + e.what());
  }
  try {
    ValidateAccuracyOptions(p.accuracy);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("parameters ~accuracy (tolerance), ~min_dt, ~max_dt: ") +
                                e.what());
  }
  if (!(p.real_time_factor >= 0.0)) {
    throw std::invalid_argument("parameter ~real_time_factor: must be >= 0 (0 = as fast as "
                                "possible), got " + std::to_string(p.real_time_factor));
  }
  if (!(p.duration >= 0.0)) {
    throw std::invalid_argument("parameter ~duration: must be >= 0 [s] (0 = run on), got " +
                                std::to_string(p.duration));
  }
  RequireRate("tf_rate", p.tf_rate, true);
  RequireRate("contacts_rate", p.contacts_rate, true);
  RequireRate("state_rate", p.state_rate, true);
  RequireRate("markers_rate", p.markers_rate, true);
  RequireRate("clock_rate", p.clock_rate, false);
  RequireRate("diagnostics_rate", p.diagnostics_rate, false);
  RequireRate("wall_update_rate", p.wall_update_rate, false);
  if (p.queue_size < 1) throw std::invalid_argument("parameter ~queue_size: must be >= 1");
  RequireRate("max_wall_publish_rate", p.max_wall_publish_rate, true);
  if (p.max_samples_per_message < 1 || p.max_samples_per_message > kMaxSamplesPerMessage) {
    throw std::invalid_argument("parameter ~max_samples_per_message: must be >= 1 and <= " +
                                std::to_string(kMaxSamplesPerMessage) + " (1 = one sample per "
                                "message), got " + std::to_string(p.max_samples_per_message));
  }
  if (!(p.marker_force_scale >= 0.0) || !(p.marker_torque_scale >= 0.0)) {
    throw std::invalid_argument("parameters ~marker_force_scale, ~marker_torque_scale: >= 0");
  }
}

NodeParameters ReadNodeParameters(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh) {
  const ParameterReader r(private_nh);
  NodeParameters p;
  // explicit while Δt·|ω| is in its safe range, implicit midpoint beyond (as simulate)
  p.simulator.gyroscopic = GyroscopicScheme::kAuto;
  // the second-order scheme (as simulate)
  p.simulator.integrator = Integrator::kMoreau2;

  // the bound first: ~urdf_file is read with it
  int max_urdf_bytes = static_cast<int>(p.scene.max_bytes);
  r.Integer("max_urdf_bytes", &max_urdf_bytes);
  if (max_urdf_bytes < 1 ||
      static_cast<std::size_t>(max_urdf_bytes) > scene_io::kMaxInputBytesOption) {
    r.Fail("max_urdf_bytes", "must be in [1, " +
                                 std::to_string(scene_io::kMaxInputBytesOption) +
                                 "] [bytes], got " + std::to_string(max_urdf_bytes));
  }
  p.scene.max_bytes = static_cast<std::size_t>(max_urdf_bytes);
  r.String("urdf_file", &p.urdf_file);
  if (!p.urdf_file.empty()) {
    p.urdf_xml = ReadFile(p.urdf_file, p.scene.max_bytes);
    // relative <mesh filename>s from the URDF file's folder, as simulate reads them
    p.scene.mesh_directory = std::filesystem::path(p.urdf_file).parent_path().string();
    if (p.scene.mesh_directory.empty()) p.scene.mesh_directory = ".";
  } else if (!nh.getParam("robot_description", p.urdf_xml)) {
    throw std::invalid_argument(
        "no URDF: set the robot_description parameter (a string) or ~urdf_file");
  } else if (p.urdf_xml.size() > p.scene.max_bytes) {
    throw std::invalid_argument(
        "parameter robot_description: " + std::to_string(p.urdf_xml.size()) +
        " bytes, more than the bound ~max_urdf_bytes = " +
        scene_io::DescribeBytes(p.scene.max_bytes));
  }
  r.String("world_frame", &p.world_frame);
  r.String("model_name", &p.model_name);

  // scene
  r.Number("gravity", &p.scene.gravity);
  std::string name = std::string(FrictionSetName(p.scene.friction_set));
  r.String("friction_set", &name);
  const auto set = FrictionSetFromName(name);
  if (!set) {
    r.Fail("friction_set", "unknown friction set \"" + name + "\", expected one of " +
                               FrictionSetNameList());
  }
  p.scene.friction_set = *set;
  p.scene.mu = r.Number("mu");
  p.scene.contact_radius = r.Number("contact_radius");
  p.scene.rolling_resistance = r.Number("rolling_resistance");
  // the start-up URDF's joints held rigid (not applied to ~spawn_urdf_model's models)
  r.Strings("hold_joints", &p.scene.hold_joints);

  // simulator and solver
  r.Number("time_step", &p.simulator.time_step);
  name = std::string(SolverTypeName(p.simulator.solver.type));
  r.String("solver", &name);
  const auto solver = SolverTypeFromName(name);
  if (!solver) {
    r.Fail("solver", "unknown solver \"" + name + "\", expected one of " + SolverTypeNameList());
  }
  p.simulator.solver.type = *solver;
  r.Number("tolerance", &p.simulator.solver.tolerance_rel);
  r.Number("tolerance_abs", &p.simulator.solver.tolerance_abs);
  r.Integer("max_iterations", &p.simulator.solver.max_iterations);
  r.Number("relaxation", &p.simulator.solver.relaxation);
  name = std::string(GyroscopicSchemeName(p.simulator.gyroscopic));
  r.String("gyroscopic", &name);
  const auto gyroscopic = GyroscopicSchemeFromName(name);
  if (!gyroscopic) {
    r.Fail("gyroscopic", "unknown scheme \"" + name +
                             "\", expected auto, explicit or implicit_midpoint");
  }
  p.simulator.gyroscopic = *gyroscopic;
  name = std::string(IntegratorName(p.simulator.integrator));
  r.String("integrator", &name);
  const auto integrator = IntegratorFromName(name);
  if (!integrator) {
    r.Fail("integrator", "unknown integrator \"" + name + "\", expected moreau2 or moreau");
  }
  p.simulator.integrator = *integrator;
  r.Bool("gap_correction", &p.simulator.gap_correction);
  r.Bool("extrapolate_warm_start", &p.simulator.extrapolate_warm_start);
  r.Number("accuracy", &p.accuracy.tolerance);
  r.Number("min_dt", &p.accuracy.min_time_step);
  r.Number("max_dt", &p.accuracy.max_time_step);

  // initial conditions
  p.initial_state = ReadInitialState(r);
  r.String("initial/body", &p.initial_body);
  p.initial.inclination = r.Number("initial/inclination");
  p.initial.spin = r.Number("initial/spin");
  if (auto v = r.Numbers("initial/position", 3)) p.initial.position = Eigen::Vector3d(*v);
  if (auto v = r.Numbers("initial/orientation", 4)) {
    p.initial.orientation = Eigen::Quaterniond((*v)[3], (*v)[0], (*v)[1], (*v)[2]);
  }
  if (auto v = r.Numbers("initial/linear_velocity", 3)) {
    p.initial.linear_velocity = Eigen::Vector3d(*v);
  }
  if (auto v = r.Numbers("initial/angular_velocity", 3)) {
    p.initial.angular_velocity = Eigen::Vector3d(*v);
  }

  // running and publishing
  r.Number("real_time_factor", &p.real_time_factor);
  r.Bool("paused", &p.paused);
  r.Number("duration", &p.duration);
  r.Number("tf_rate", &p.tf_rate);
  r.Number("contacts_rate", &p.contacts_rate);
  r.Number("state_rate", &p.state_rate);
  r.Number("markers_rate", &p.markers_rate);
  r.Number("clock_rate", &p.clock_rate);
  r.Number("diagnostics_rate", &p.diagnostics_rate);
  r.Number("wall_update_rate", &p.wall_update_rate);
  r.Integer("queue_size", &p.queue_size);
  r.Number("max_wall_publish_rate", &p.max_wall_publish_rate);
  r.Integer("max_samples_per_message", &p.max_samples_per_message);
  r.Number("marker_force_scale", &p.marker_force_scale);
  r.Number("marker_torque_scale", &p.marker_torque_scale);

  ValidateNodeParameters(p);
  return p;
}

}  // namespace nonsmooth_sim::node
