// Per-step monitors and the decimated CSV of `simulate`.
#include "monitor.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/world/lost_bodies.h"

namespace nonsmooth_sim::simulate {
namespace {

// Inclination thresholds of the summary [rad]: horizontal, peg touchdown (both spheres touch at
// θ* ≈ 2.449), inverted.
constexpr double kThetaHorizontal = 0.5 * kPi;
constexpr double kThetaPegTouchdown = 2.4;
constexpr double kThetaInverted = 2.9;
constexpr int kSignificantDigits = 15;  // of the CSV numbers

// cos θ = e3·ẑ = 1 - 2(x² + y²) of a unit quaternion: threshold tests without acos
double CosInclination(const Eigen::Quaterniond& p) {
  return 1.0 - 2.0 * (p.x() * p.x() + p.y() * p.y());
}

void SetOnce(std::optional<double>* time, double t) {
  if (!*time) *time = t;
}

}  // namespace

double VerticalSpin(const BodyState& state) {
  return (state.orientation * state.angular_velocity).z();
}

RunMonitor::RunMonitor(const RunConfig& config, const Simulator& simulator)
    : tippe_top_(config.urdf_path.empty()) {
  summary_.config = config;
  summary_.tippe_top = tippe_top_;
  const BodyState& s = simulator.state()[0];
  summary_.energy_initial = simulator.Energy();
  if (tippe_top_) {
    summary_.jellett_initial = JellettIntegral(simulator.scene(), simulator.state(), kBigSphere);
  }
  summary_.vertical_spin_initial = VerticalSpin(s);
  min_cos_theta_ = std::cos(Inclination(s));
  summary_.min_gap = std::numeric_limits<double>::infinity();
  summary_.max_energy_increase = -std::numeric_limits<double>::infinity();
  energy_previous_ = summary_.energy_initial;
}

void RunMonitor::Observe(long step, double t, double dt, const Simulator& simulator,
                         const StepStatistics& stats) {
  const BodyState& s = simulator.state()[0];
  const auto& contacts = simulator.contacts();

  // energy: largest increase over one step and over the start
  const double energy = stats.energy;  // Energy() of the state after the step
  if (energy - energy_previous_ > summary_.max_energy_increase) {
    summary_.max_energy_increase = energy - energy_previous_;
    summary_.max_energy_increase_time = t;
  }
  summary_.max_energy_above_initial =
      std::max(summary_.max_energy_above_initial, energy - summary_.energy_initial);
  energy_previous_ = energy;

  // inclination thresholds, tested on cos θ
  const double cos_theta = CosInclination(s.orientation);
  if (cos_theta < std::cos(kThetaHorizontal)) SetOnce(&summary_.t_theta_above_pi_2, t);
  if (cos_theta < std::cos(kThetaPegTouchdown)) SetOnce(&summary_.t_theta_above_2_4, t);
  if (cos_theta < std::cos(kThetaInverted)) SetOnce(&summary_.t_theta_above_2_9, t);
  min_cos_theta_ = std::min(min_cos_theta_, cos_theta);

  // contact phases of the Tippe-Top
  if (tippe_top_) {
    const bool big = simulator.InContact(kBigSphere);
    const bool peg = simulator.InContact(kPegSphere);
    if (peg) SetOnce(&summary_.t_peg_touchdown, t);
    if (peg && !big) {
      SetOnce(&summary_.t_big_sphere_liftoff, t);
      peg_only_time_ += dt;
    }
    if (big && summary_.t_theta_above_2_9) SetOnce(&summary_.t_fall_back, t);
  }
  for (const ContactState& c : contacts) summary_.min_gap = std::min(summary_.min_gap, c.gap);
  summary_.max_closed_contacts = std::max(summary_.max_closed_contacts, stats.closed_contacts);
  summary_.max_islands = std::max(summary_.max_islands, stats.islands);
  summary_.max_penetration = std::max(summary_.max_penetration, stats.max_penetration);

  // solver
  total_iterations_ += stats.solver.iterations;
  summary_.max_iterations = std::max(summary_.max_iterations, stats.solver.iterations);
  if (!stats.solver.converged) ++summary_.unconverged_steps;
  summary_.max_dt_omega = std::max(summary_.max_dt_omega, stats.max_dt_omega);
  if (stats.explicit_gyroscopic_unsafe && summary_.explicit_gyroscopic_safe) {
    summary_.explicit_gyroscopic_safe = false;
    summary_.t_explicit_gyroscopic_unsafe = t;
    summary_.explicit_gyroscopic_unsafe_dt_omega = stats.max_dt_omega;
  }

  // gap correction (a position projection outside the paper's scheme)
  if (stats.gap_correction > 0.0) ++summary_.gap_correction_steps;
  summary_.gap_correction_max = std::max(summary_.gap_correction_max, stats.gap_correction);
  summary_.gap_correction_energy += stats.gap_correction_energy;
  summary_.steps = step;
}

void RunMonitor::ObserveNonFinite(double t) {
  summary_.state_finite = false;
  summary_.t_non_finite = t;
}

std::vector<LostBodyRecord> RunMonitor::CheckLostBodies(double t, const Simulator& simulator) {
  std::vector<LostBodyRecord> found;
  const Scene& scene = simulator.scene();
  for (const world::LostBody& lost : world::FindLostBodies(scene, simulator.state())) {
    const std::string& name = scene.bodies[static_cast<std::size_t>(lost.body)].name;
    const auto seen = std::find_if(summary_.lost_bodies.begin(), summary_.lost_bodies.end(),
                                   [&](const LostBodyRecord& r) { return r.name == name; });
    if (seen != summary_.lost_bodies.end()) continue;
    found.push_back({name, t, world::DescribeLostBody(lost)});
    summary_.lost_bodies.push_back(found.back());
  }
  return found;
}

RunSummary RunMonitor::Finish(const Simulator& simulator) {
  const BodyState& s = simulator.state()[0];
  summary_.theta_final = Inclination(s);
  summary_.theta_max = std::acos(std::clamp(min_cos_theta_, -1.0, 1.0));
  summary_.z_final = s.position.z();
  summary_.energy_final = simulator.Energy();
  if (tippe_top_) {
    summary_.jellett_final = JellettIntegral(simulator.scene(), simulator.state(), kBigSphere);
  }
  summary_.vertical_spin_final = VerticalSpin(s);
  for (std::size_t b = 0; b < simulator.scene().bodies.size(); ++b) {
    const RigidBody& body = simulator.scene().bodies[b];
    const BodyState& state = simulator.state()[b];
    summary_.body_names.push_back(body.name);
    summary_.final_link_position.push_back(state.position - state.orientation * body.com_in_link);
    summary_.final_state.push_back(state);
  }
  summary_.time_on_peg_s = peg_only_time_;
  summary_.mean_iterations =
      summary_.steps > 0 ? static_cast<double>(total_iterations_) / summary_.steps : 0.0;
  if (summary_.steps == 0) summary_.max_energy_increase = 0.0;
  return summary_;
}

CsvRecorder::CsvRecorder(const Simulator& simulator, long expected_rows) {
  columns_ = {"t",  "x_s", "y_s",   "z_s",    "qw",      "qx",
              "qy", "qz",  "theta", "energy", "jellett", "vertical_spin"};
  const std::vector<Collider>& colliders = simulator.scene().colliders;
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    if (colliders[i].body != 0 || colliders[i].shape.type != ShapeType::kSphere) continue;
    spheres_.push_back(static_cast<int>(i));
    for (const char* field : {"_closed", "_lambda_n", "_lambda_t1", "_lambda_t2", "_lambda_tau"}) {
      columns_.push_back(colliders[i].name + field);
    }
    // the rolling percussion only where the sphere's law has rolling components (the ground's
    // law is neutral: the sphere's decides)
    sphere_rolling_.push_back(HasRolling(colliders[i].law) ? 1 : 0);
    if (sphere_rolling_.back() != 0) {
      for (const char* field : {"_lambda_r1", "_lambda_r2"}) {
        columns_.push_back(colliders[i].name + field);
      }
    }
  }
  columns_.push_back("iterations");
  columns_.push_back("converged");
  values_.reserve(static_cast<std::size_t>(expected_rows) * columns_.size());
}

void CsvRecorder::Record(double time, const Simulator& simulator, const StepStatistics& stats) {
  const BodyState& s = simulator.state()[0];
  const double row[] = {time,
                        s.position.x(),
                        s.position.y(),
                        s.position.z(),
                        s.orientation.w(),
                        s.orientation.x(),
                        s.orientation.y(),
                        s.orientation.z(),
                        Inclination(s),
                        simulator.Energy(),
                        JellettIntegral(simulator.scene(), simulator.state(), kBigSphere),
                        VerticalSpin(s)};
  values_.insert(values_.end(), std::begin(row), std::end(row));
  // per sphere: its (one) ground contact, closed or not
  for (std::size_t n = 0; n < spheres_.size(); ++n) {
    const int sphere = spheres_[n];
    const ContactState* contact = nullptr;
    for (const ContactState& c : simulator.contacts()) {
      if (c.collider_a == sphere || c.collider_b == sphere) contact = &c;
    }
    values_.push_back(contact != nullptr ? 1.0 : 0.0);
    for (int k = 0; k < 4; ++k)
      values_.push_back(contact != nullptr ? contact->percussion[k] : 0.0);
    if (sphere_rolling_[n] == 0) continue;
    for (int k = 0; k < 2; ++k) {
      values_.push_back(contact != nullptr ? contact->rolling_percussion[k] : 0.0);
    }
  }
  values_.push_back(stats.solver.iterations);
  values_.push_back(stats.solver.converged ? 1.0 : 0.0);
}

bool CsvRecorder::Write(const std::string& path) const { return WriteCsv(columns_, values_, path); }

BodyCsvRecorder::BodyCsvRecorder(const Simulator& simulator, long expected_rows) {
  columns_ = {"t"};
  for (const RigidBody& body : simulator.scene().bodies) {
    for (const char* field :
         {"x", "y", "z", "qx", "qy", "qz", "qw", "vx", "vy", "vz", "wx", "wy", "wz"}) {
      columns_.push_back(body.name + "/" + field);
    }
  }
  for (const char* field :
       {"energy", "closed_contacts", "islands", "max_penetration", "iterations", "converged"}) {
    columns_.push_back(field);
  }
  values_.reserve(static_cast<std::size_t>(expected_rows) * columns_.size());
}

BodyCsvRecorder::BodyCsvRecorder(const std::vector<std::string>& bodies, long expected_rows)
    : bodies_(bodies) {
  columns_ = {"t"};
  for (const std::string& body : bodies) {
    for (const char* field :
         {"x", "y", "z", "qx", "qy", "qz", "qw", "vx", "vy", "vz", "wx", "wy", "wz"}) {
      columns_.push_back(body + "/" + field);
    }
  }
  for (const char* field :
       {"energy", "closed_contacts", "islands", "max_penetration", "iterations", "converged"}) {
    columns_.push_back(field);
  }
  values_.reserve(static_cast<std::size_t>(expected_rows) * columns_.size());
}

void BodyCsvRecorder::Record(double time, const Simulator& simulator, const StepStatistics& stats) {
  values_.push_back(time);
  if (bodies_.empty()) {
    for (std::size_t b = 0; b < simulator.scene().bodies.size(); ++b) AppendBody(simulator, b);
  } else {
    // by name: a body that is not there (not yet spawned, or deleted) writes NaN
    for (const std::string& name : bodies_) {
      std::size_t b = 0;
      while (b < simulator.scene().bodies.size() && simulator.scene().bodies[b].name != name) ++b;
      if (b < simulator.scene().bodies.size()) {
        AppendBody(simulator, b);
      } else {
        values_.insert(values_.end(), 13, std::numeric_limits<double>::quiet_NaN());
      }
    }
  }
  values_.push_back(simulator.Energy());
  values_.push_back(stats.closed_contacts);
  values_.push_back(stats.islands);
  values_.push_back(stats.max_penetration);
  values_.push_back(stats.solver.iterations);
  values_.push_back(stats.solver.converged ? 1.0 : 0.0);
}

void BodyCsvRecorder::AppendBody(const Simulator& simulator, std::size_t b) {
  {
    const BodyState& s = simulator.state()[b];
    // the link frame: r_S - A com_in_link; ω in the world
    const Eigen::Vector3d link =
        s.position - s.orientation * simulator.scene().bodies[b].com_in_link;
    const Eigen::Vector3d omega = s.orientation * s.angular_velocity;
    const double row[] = {link.x(),
                          link.y(),
                          link.z(),
                          s.orientation.x(),
                          s.orientation.y(),
                          s.orientation.z(),
                          s.orientation.w(),
                          s.linear_velocity.x(),
                          s.linear_velocity.y(),
                          s.linear_velocity.z(),
                          omega.x(),
                          omega.y(),
                          omega.z()};
    values_.insert(values_.end(), std::begin(row), std::end(row));
  }
}

bool BodyCsvRecorder::Write(const std::string& path) const {
  return WriteCsv(columns_, values_, path);
}

bool WriteCsv(const std::vector<std::string>& columns, const std::vector<double>& values,
              const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return false;
  std::string text;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    text += columns[k];
    text += k + 1 < columns.size() ? ',' : '\n';
  }
  char buffer[32];
  for (std::size_t k = 0; k < values.size(); ++k) {
    // 15 significant digits: t = k·Δt prints as 0.003, not 0.0030000000000000001
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), values[k],
                                      std::chars_format::general, kSignificantDigits);
    text.append(buffer, result.ptr);
    text += (k + 1) % columns.size() == 0 ? '\n' : ',';
  }
  const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  return std::fclose(file) == 0 && ok;
}

}  // namespace nonsmooth_sim::simulate
