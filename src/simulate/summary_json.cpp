// The JSON summary of a `simulate` run (field names are part of the interface: scripts/demo and
// the README read them).
#include <Eigen/Core>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "monitor.h"

namespace nonsmooth_sim::simulate {
namespace {

constexpr int kSignificantDigits = 15;

class JsonObject {
 public:
  void Add(const char* key, const std::string& value) {
    Key(key);
    text_ += '"';
    text_ += value;  // names and enums only: no characters that need escaping
    text_ += '"';
  }
  void Add(const char* key, double value) {
    Key(key);
    // JSON has no inf or NaN (a run without contacts has no smallest gap): null
    if (!std::isfinite(value)) {
      text_ += "null";
      return;
    }
    // 15 significant digits: times k·Δt print as 1.3695, not 1.3695000000000002
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value,
                                      std::chars_format::general, kSignificantDigits);
    text_.append(buffer, result.ptr);
  }
  void Add(const char* key, long value) { Add(key, static_cast<double>(value)); }
  void Add(const char* key, int value) { Add(key, static_cast<double>(value)); }
  void Add(const char* key, bool value) {
    Key(key);
    text_ += value ? "true" : "false";
  }
  void Add(const char* key, const std::optional<double>& value) {
    if (value) {
      Add(key, *value);
    } else {
      Key(key);
      text_ += "null";
    }
  }
  /// A value written as JSON already (an array or object).
  void AddRaw(const char* key, const std::string& json) {
    Key(key);
    text_ += json;
  }
  std::string Text() const { return text_ + "\n}\n"; }

 private:
  void Key(const char* key) {
    text_ += text_.empty() ? "{\n  \"" : ",\n  \"";
    text_ += key;
    text_ += "\": ";
  }
  std::string text_;
};

std::string Number(double value) {
  if (!std::isfinite(value)) return "null";  // as JsonObject::Add
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value,
                                    std::chars_format::general, kSignificantDigits);
  return std::string(buffer, result.ptr);
}

template <typename Vector>
std::string Array(const Vector& v) {
  std::string out = "[";
  for (Eigen::Index k = 0; k < v.size(); ++k) out += (k > 0 ? ", " : "") + Number(v[k]);
  return out + "]";
}

// "text" with " and \ escaped (URDF names may hold them; they hold no control characters)
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// {"<link>": {"position": [...], "orientation": [qx, qy, qz, qw], "linear_velocity": [...],
// "angular_velocity": [...]}, ...}: the YAML initial-state convention, so a run can continue
std::string Bodies(const RunSummary& s) {
  std::string out = "{";
  for (std::size_t b = 0; b < s.body_names.size(); ++b) {
    const BodyState& state = s.final_state[b];
    out += (b > 0 ? ",\n    " : "\n    ") + Quoted(s.body_names[b]) + ": {\"position\": " +
           Array(s.final_link_position[b]) + ", \"orientation\": " +
           Array(state.orientation.coeffs()) + ", \"linear_velocity\": " +
           Array(state.linear_velocity) + ", \"angular_velocity\": " +
           Array(state.angular_velocity) + "}";
  }
  return out + "\n  }";
}

// {"<body>": {"t": ..., "why": "..."}, ...}: the bodies that could no longer touch anything
std::string LostBodies(const RunSummary& s) {
  std::string out = "{";
  for (std::size_t k = 0; k < s.lost_bodies.size(); ++k) {
    const LostBodyRecord& r = s.lost_bodies[k];
    out += (k > 0 ? ", " : "") + Quoted(r.name) + ": {\"t\": " + Number(r.t) +
           ", \"why\": " + Quoted(r.why) + "}";
  }
  return out + "}";
}

}  // namespace

bool WriteSummaryJson(const RunSummary& s, const std::string& path) {
  const RunConfig& c = s.config;
  JsonObject json;
  // the fields of the issue, in its order
  json.Add("friction_set", std::string(FrictionSetName(c.parameters.friction_set)));
  json.Add("solver", std::string(SolverTypeName(c.options.solver.type)));
  json.Add("dt", c.options.time_step);
  json.Add("duration", c.duration);
  json.Add("steps", s.steps);
  json.Add("wall_time_s", s.wall_time_s);
  json.Add("steps_per_second", s.wall_time_s > 0.0 ? s.steps / s.wall_time_s : 0.0);
  json.Add("t_theta_above_pi_2", s.t_theta_above_pi_2);
  json.Add("t_theta_above_2_4", s.t_theta_above_2_4);
  json.Add("theta_final", s.theta_final);
  json.Add("z_final", s.z_final);
  json.Add("energy_initial", s.energy_initial);
  json.Add("energy_final", s.energy_final);
  json.Add("max_energy_increase", s.max_energy_increase);
  json.Add("jellett_initial", s.tippe_top ? std::optional<double>(s.jellett_initial) : std::nullopt);
  json.Add("jellett_final", s.tippe_top ? std::optional<double>(s.jellett_final) : std::nullopt);
  json.Add("mean_iterations", s.mean_iterations);
  json.Add("max_iterations", s.max_iterations);
  json.Add("unconverged_steps", s.unconverged_steps);
  // extras
  json.Add("gyroscopic", std::string(GyroscopicSchemeName(c.options.gyroscopic)));
  json.Add("integrator", std::string(IntegratorName(c.options.integrator)));
  // --accuracy (0: fixed steps): the step-size control's counts
  json.Add("accuracy", c.accuracy.tolerance);
  if (s.adaptive) {
    const AdaptiveStatistics& a = *s.adaptive;
    json.Add("min_dt", c.accuracy.min_time_step);
    json.Add("max_dt", c.accuracy.max_time_step);
    json.Add("accepted_steps", a.accepted_steps);
    json.Add("rejected_steps", a.rejected_steps);
    json.Add("forced_steps", a.forced_steps);
    json.Add("simulator_steps", a.simulator_steps);
    json.Add("smallest_step", a.accepted_steps > 0 ? a.smallest_step : 0.0);
    json.Add("largest_step", a.largest_step);
    json.Add("max_error_estimate", a.max_error);
    json.Add("mean_error_estimate",
             a.accepted_steps > 0 ? a.error_sum / static_cast<double>(a.accepted_steps) : 0.0);
  }
  json.Add("tolerance_rel", c.options.solver.tolerance_rel);
  json.Add("tolerance_abs", c.options.solver.tolerance_abs);
  json.Add("solver_max_iterations", c.options.solver.max_iterations);
  json.Add("relaxation", c.options.solver.relaxation);
  json.Add("map_drilling_sets", c.options.solver.map_drilling_sets);
  json.Add("direct_solve", c.options.solver.direct_solve);
  json.Add("mu", c.parameters.mu);
  json.Add("contact_radius", c.parameters.contact_radius);
  json.Add("inclination_initial", c.initial.inclination);
  json.Add("spin_initial", c.initial.spin);
  json.Add("real_time_factor", s.wall_time_s > 0.0 ? c.duration / s.wall_time_s : 0.0);
  json.Add("cpu_time_s", s.cpu_time_s);
  json.Add("output_wall_time_s", s.output_wall_time_s);
  json.Add("t_theta_above_2_9", s.t_theta_above_2_9);
  json.Add("t_peg_touchdown", s.t_peg_touchdown);
  json.Add("t_big_sphere_liftoff", s.t_big_sphere_liftoff);
  json.Add("t_fall_back", s.t_fall_back);
  json.Add("time_on_peg_s", s.time_on_peg_s);
  json.Add("theta_max", s.theta_max);
  json.Add("max_energy_increase_time", s.max_energy_increase_time);
  json.Add("max_energy_above_initial", s.max_energy_above_initial);
  json.Add("vertical_spin_initial", s.vertical_spin_initial);
  json.Add("vertical_spin_final", s.vertical_spin_final);
  json.Add("min_gap", s.min_gap);
  json.Add("max_dt_omega", s.max_dt_omega);
  json.Add("explicit_gyroscopic_safe", s.explicit_gyroscopic_safe);
  json.Add("t_explicit_gyroscopic_unsafe", s.t_explicit_gyroscopic_unsafe);
  json.Add("gap_correction", c.options.gap_correction);
  json.Add("extrapolate_warm_start", c.options.extrapolate_warm_start);
  json.Add("gap_correction_max", s.gap_correction_max);
  json.Add("gap_correction_energy", s.gap_correction_energy);
  json.Add("gap_correction_steps", s.gap_correction_steps);
  json.Add("state_finite", s.state_finite);
  json.Add("t_non_finite", s.t_non_finite);
  // every scene: what it contains and how the contacts went, and where each body ended
  json.Add("scene", c.urdf_path.empty() ? std::string("tippe_top (built in)") : c.urdf_path);
  json.Add("max_closed_contacts", s.max_closed_contacts);
  json.Add("max_islands", s.max_islands);
  json.Add("max_penetration", s.max_penetration);
  json.AddRaw("bodies", Bodies(s));
  json.AddRaw("lost_bodies", LostBodies(s));

  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return false;
  const std::string text = json.Text();
  const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  return std::fclose(file) == 0 && ok;
}

}  // namespace nonsmooth_sim::simulate
