// Shared pieces of the scene tests (test/scenes/*_test.cpp): load a shipped scene (urdf/<name>.urdf
// through the scene loader, the start from config/<name>.yaml), step it while checking the
// invariants every scene must keep, and a few observables.
//
// config/<scene>.yaml is read by the scene loader's ParseInitialStateYaml (scene_io/
// initial_state.h: the link frame's position and orientation, v_S, K_ω in link axes). The shipped
// scenes put the link frame at the centre of mass, so the link's position is that of S.
//
// Energy per step (Runner::Step): with ε = 0 and W taken at q_M, a step of the Moreau midpoint scheme
// changes the kinetic plus potential energy by exactly Λᵀ(γ_E + γ_B)/2 (gravity's work cancels the
// potential change), which is ≤ 0 when the law holds at γ_E and no closed contact is separating at
// the start of the step (γ_N^B ≤ 0; rattleback_test.cpp shows a case where one is), plus, with the explicit gyroscopic term, ½Δt²·aᵀΘa per body,
// a = Θ⁻¹(ω_B × Θω_B) (the gain of a step without contact, simulator.h), plus the potential energy
// the gap correction lifts add (StepStatistics::gap_correction_energy). Runner::Step allows exactly
// these and round-off (1e-12 of the energy scale), and records the largest excess.
#ifndef NONSMOOTH_SIM_TEST_SCENES_SCENE_TEST_SUPPORT_H_
#define NONSMOOTH_SIM_TEST_SCENES_SCENE_TEST_SUPPORT_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_test {

/// <source>/<relative>.
inline std::string SourcePath(const std::string& relative) {
  return std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/" + relative;
}

/// Index of the body named `name` (its link), or throws.
inline int BodyIndex(const Scene& scene, const std::string& name) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].name == name) return static_cast<int>(b);
  }
  throw std::invalid_argument("no body named " + name);
}

/// urdf/<name>.urdf through the scene loader (with `options`; package:// finds this source
/// tree), started from config/<name>.yaml.
inline Scene LoadShippedScene(const std::string& name,
                              scene_io::UrdfSceneOptions options = {}) {
  // package://nonsmooth_sim/ meshes (urdf/d20.urdf): this source tree, whatever the environment
  if (!options.ros_package_path) options.ros_package_path = SourcePath("");
  const scene_io::UrdfScene urdf = scene_io::LoadUrdfFile(SourcePath("urdf/" + name + ".urdf"),
                                                          options);
  Scene scene = urdf.scene;
  scene.initial_state =
      scene_io::InitialStateFromYamlFile(scene, SourcePath("config/" + name + ".yaml"));
  return scene;
}

/// ½Δt²·aᵀΘa summed over the bodies, a = Θ⁻¹(ω × Θω): the energy a step of the explicit
/// gyroscopic scheme adds without contact (simulator.h) [J].
inline double ExplicitGyroscopicGain(const Scene& scene, const std::vector<BodyState>& state,
                                     double dt) {
  double gain = 0.0;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const Eigen::Matrix3d& theta = scene.bodies[b].inertia;
    const Eigen::Vector3d& w = state[b].angular_velocity;
    const Eigen::Vector3d a = theta.inverse() * w.cross(theta * w);
    gain += 0.5 * dt * dt * a.dot(theta * a);
  }
  return gain;
}

/// Steps a simulator and keeps the invariants of every scene: finite, energy not increasing
/// beyond the allowance of the top of this file, and the largest penetration.
class Runner {
 public:
  explicit Runner(Simulator* simulator) : sim_(simulator) {}

  /// One step; returns its statistics.
  const StepStatistics& Step() {
    const double before = sim_->Energy();
    const double gyroscopic =
        sim_->options().gyroscopic == GyroscopicScheme::kExplicit
            ? ExplicitGyroscopicGain(sim_->scene(), sim_->state(), sim_->options().time_step)
            : 0.0;
    sim_->Step(&stats_);
    finite_ = finite_ && stats_.state_finite;
    const double after = sim_->Energy();
    // round-off: 1e-12 of the energy scale. The state itself rounds at 1e-16; the solver stops at
    // tolerance_rel = 1e-5, which leaves γ_E at that level on contacts that carry Λ ~ m g Δt and
    // moves energy by ~1e-13 of the scale in a step (measured up to 3.6e-13 on the resting die)
    const double round_off = 1e-12 * (std::abs(before) + EnergyScale());
    const double excess = (after - before) - stats_.gap_correction_energy - gyroscopic - round_off;
    if (excess > max_energy_excess_) {
      max_energy_excess_ = excess;
      max_energy_excess_time_ = sim_->time();
    }
    if (excess > 0.0) {
      ++energy_excess_steps_;
      total_energy_excess_ += excess;
    }
    max_energy_increase_ = std::max(max_energy_increase_, after - before);
    gap_correction_energy_ += stats_.gap_correction_energy;
    max_penetration_ = std::max(max_penetration_, stats_.max_penetration);
    max_iterations_ = std::max(max_iterations_, stats_.solver.iterations);
    all_converged_ = all_converged_ && stats_.solver.converged;
    return stats_;
  }
  /// Steps until time() ≥ t_end (to within a tenth of a step).
  void RunUntil(double t_end) {
    while (sim_->time() < t_end - 0.1 * sim_->options().time_step && finite_) Step();
  }

  bool finite() const { return finite_; }
  /// Largest (ΔE − allowance) of a step; ≤ 0 when the energy never rose beyond it [J].
  double max_energy_excess() const { return max_energy_excess_; }
  double max_energy_excess_time() const { return max_energy_excess_time_; }
  /// Steps with a positive excess, and the sum of those excesses [J].
  int energy_excess_steps() const { return energy_excess_steps_; }
  double total_energy_excess() const { return total_energy_excess_; }
  /// Largest raw ΔE of a step [J].
  double max_energy_increase() const { return max_energy_increase_; }
  /// Σ gap_correction_energy over the steps [J].
  double gap_correction_energy() const { return gap_correction_energy_; }
  /// Largest StepStatistics::max_penetration [m].
  double max_penetration() const { return max_penetration_; }
  int max_iterations() const { return max_iterations_; }
  bool all_converged() const { return all_converged_; }
  const StepStatistics& last() const { return stats_; }

 private:
  // Σ m g |z| + kinetic: the size of the numbers the energy is a difference of
  double EnergyScale() const {
    double scale = 0.0;
    const Scene& scene = sim_->scene();
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      const BodyState& s = sim_->state()[b];
      scale += scene.bodies[b].mass * (scene.gravity.norm() * std::abs(s.position.z()) +
                                       s.linear_velocity.squaredNorm()) +
               s.angular_velocity.dot(scene.bodies[b].inertia * s.angular_velocity);
    }
    return scale;
  }

  Simulator* sim_;
  StepStatistics stats_;
  bool finite_ = true;
  double max_energy_excess_ = -std::numeric_limits<double>::infinity();
  double max_energy_excess_time_ = 0.0;
  int energy_excess_steps_ = 0;
  double total_energy_excess_ = 0.0;
  double max_energy_increase_ = -std::numeric_limits<double>::infinity();
  double gap_correction_energy_ = 0.0;
  double max_penetration_ = 0.0;
  int max_iterations_ = 0;
  bool all_converged_ = true;
};

/// e3 of a body in the world.
inline Eigen::Vector3d AxisE3(const BodyState& s) {
  return s.orientation.normalized() * Eigen::Vector3d::UnitZ();
}

/// ω in the world frame [rad/s].
inline Eigen::Vector3d WorldAngularVelocity(const BodyState& s) {
  return s.orientation.normalized() * s.angular_velocity;
}

/// Lowest point of a collider's shape (sphere, ellipsoid) of body state `s` in the world: the
/// support point along −z [m].
inline Eigen::Vector3d LowestPoint(const Collider& collider, const BodyState& s) {
  const Eigen::Isometry3d pose = BodyPose(s) * collider.pose;
  const Eigen::Vector3d d = -(pose.linear().transpose() * Eigen::Vector3d::UnitZ());
  Eigen::Vector3d axes = Eigen::Vector3d::Constant(collider.shape.radius);
  if (collider.shape.type == ShapeType::kEllipsoid) axes = collider.shape.half_extents;
  const Eigen::Vector3d s_d = axes.cwiseProduct(d);
  return pose * Eigen::Vector3d(axes.cwiseProduct(s_d) / s_d.norm());
}

/// Largest speed of any point of a body: |v_S| + |ω| ρ with ρ the bounding radius of its
/// colliders about S [m/s].
inline double MaxPointSpeed(const Scene& scene, const std::vector<BodyState>& state, int body) {
  double radius = 0.0;
  for (const Collider& c : scene.colliders) {
    if (c.body != body) continue;
    radius = std::max(radius, c.pose.translation().norm() + BoundingRadius(c.shape));
  }
  const BodyState& s = state[static_cast<std::size_t>(body)];
  return s.linear_velocity.norm() + s.angular_velocity.norm() * radius;
}

/// What a tossed body (body 0: the dice) did over a run: when it first touched, how far it turned
/// on the floor, when its set of contacts last changed, after t = 1 s its largest point speed
/// and penetration and its position at 1 s (for the drift), and how the run ended.
struct Toss {
  double first_contact = -1.0;   ///< [s], -1: never
  double turned_on_floor = 0.0;  ///< ∫|ω| dt after the first contact [rad]
  double last_change = 0.0;      ///< when the contact set (features) last changed [s]
  Eigen::Vector3d position_at_1s = Eigen::Vector3d::Zero();
  double max_speed_late = 0.0;        ///< over t > 1 s [m/s]
  double max_penetration_late = 0.0;  ///< over t > 1 s [m]
  BodyState end;                      ///< the state at the end
  std::size_t end_contacts = 0;       ///< closed contacts at the end
  double max_penetration = 0.0;       ///< over the run (Runner's) [m]
  double max_energy_excess = 0.0;     ///< Runner's [J]
  double max_energy_excess_time = 0.0;
  bool finite = true;
};

/// urdf/<scene>.urdf tossed from config/<scene>.yaml, moreau at Δt = 1e-4 s for `duration` [s]
/// (> 1), body 0 recorded as a Toss.
inline Toss TossShippedScene(const std::string& scene, double duration) {
  SimulatorOptions options;
  options.time_step = 1e-4;
  Simulator sim(LoadShippedScene(scene), options);
  Runner run(&sim);
  Toss toss;
  long signature = -1;  // the contact set of the last step
  const double dt = options.time_step;
  while (sim.time() < duration && run.finite()) {
    const StepStatistics& stats = run.Step();
    const BodyState& s = sim.state()[0];
    if (toss.first_contact < 0.0 && !sim.contacts().empty()) toss.first_contact = sim.time();
    if (toss.first_contact >= 0.0) toss.turned_on_floor += s.angular_velocity.norm() * dt;
    long sig = 0;
    for (const ContactState& c : sim.contacts()) sig = sig * 64 + c.feature + 1;
    if (sig != signature) {
      signature = sig;
      toss.last_change = sim.time();
    }
    if (std::abs(sim.time() - 1.0) < 0.5 * dt) toss.position_at_1s = s.position;
    if (sim.time() > 1.0) {
      toss.max_penetration_late = std::max(toss.max_penetration_late, stats.max_penetration);
      toss.max_speed_late =
          std::max(toss.max_speed_late, MaxPointSpeed(sim.scene(), sim.state(), 0));
    }
  }
  toss.end = sim.state()[0];
  toss.end_contacts = sim.contacts().size();
  toss.max_penetration = run.max_penetration();
  toss.max_energy_excess = run.max_energy_excess();
  toss.max_energy_excess_time = run.max_energy_excess_time();
  toss.finite = run.finite();
  return toss;
}

}  // namespace nonsmooth_sim::scene_test

#endif  // NONSMOOTH_SIM_TEST_SCENES_SCENE_TEST_SUPPORT_H_
