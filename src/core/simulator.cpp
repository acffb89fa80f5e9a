// Moreau midpoint time-stepping (13)-(18), see simulator.h: the step and the setters. Contact
// generation and islands are in simulator_contacts.cpp, the contact solve in simulator_solve.cpp.
#include "nonsmooth_sim/core/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "nonsmooth_sim/core/all_finite.h"

namespace nonsmooth_sim {
namespace {

constexpr double kMinTimeStep = 1e-7;  // [s]
constexpr double kMaxTimeStep = 1e-2;  // [s]
// The implicit-midpoint passes stop once ω_E changes by less than this relative amount even when
// the solver tolerance is tighter: below it the change is round-off.

std::vector<BodyState> Normalized(std::vector<BodyState> state) {
  for (BodyState& s : state) s.orientation.normalize();
  return state;
}

// ½m|v_S|² + ½ωᵀΘω - m g·r_S of one body, with the operations of MechanicalEnergy (scene.cpp), so
// that a sum of these that is finite is an Energy() that is finite.
double BodyEnergy(const RigidBody& body, const Eigen::Vector3d& gravity,
                  const Eigen::Vector3d& position, const Eigen::Vector3d& linear,
                  const Eigen::Vector3d& angular) {
  return 0.5 * body.mass * linear.squaredNorm() + 0.5 * angular.dot(body.inertia * angular) -
         body.mass * gravity.dot(position);
}

// What (13) and the free velocities produced from one body's q_B, u_B.
bool MidpointIsFinite(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                      const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  return AllFinite(position) && AllFinite(orientation.coeffs()) && AllFinite(linear) &&
         AllFinite(angular);
}

}  // namespace

void ValidateSimulatorOptions(const SimulatorOptions& options) {
  if (!(options.time_step >= kMinTimeStep && options.time_step <= kMaxTimeStep)) {
    std::ostringstream s;
    s << "SimulatorOptions.time_step = " << options.time_step << ": must be in [" << kMinTimeStep
      << ", " << kMaxTimeStep << "] s";
    throw std::invalid_argument(s.str());
  }
  // the tighter cap of a simulation first, so that the message names it
  if (options.solver.max_iterations > kMaxSimulatorIterations) {
    throw std::invalid_argument("SimulatorOptions.solver.max_iterations: must be >= 1 and <= " +
                                std::to_string(kMaxSimulatorIterations) +
                                " in a simulation (the cap multiplies the work of every step), "
                                "got " + std::to_string(options.solver.max_iterations));
  }
  ValidateSolverOptions(options.solver);
  if (GyroscopicSchemeName(options.gyroscopic) == "unknown") {
    throw std::invalid_argument(
        "SimulatorOptions.gyroscopic must be kExplicit, kImplicitMidpoint or kAuto");
  }
}

std::string ContactName(const Scene& scene, const ContactState& contact) {
  const int first = std::min(contact.collider_a, contact.collider_b);
  const int second = std::max(contact.collider_a, contact.collider_b);
  return scene.colliders[static_cast<std::size_t>(first)].name + "/" +
         scene.colliders[static_cast<std::size_t>(second)].name;
}

Simulator::Simulator(Scene scene, SimulatorOptions options)
    : scene_(std::move(scene)), options_(options) {
  ValidateScene(scene_);
  ValidateSimulatorOptions(options_);
  RequireFiniteEnergy(scene_, scene_.initial_state);
  state_ = Normalized(scene_.initial_state);
  Initialize();
}

void Simulator::Initialize() {
  BuildCaches();
  memory_.clear();
  contacts_.clear();
  wrench_.assign(scene_.bodies.size(), Wrench{});
  any_wrench_ = false;
}

void Simulator::BuildCaches() {
  const std::size_t bodies = scene_.bodies.size();
  inertia_.clear();
  for (const RigidBody& body : scene_.bodies) {
    inertia_.push_back(MakeBodyInertia(body.mass, body.inertia));
  }
  body_step_.assign(bodies, BodyStep{});
  union_find_.assign(bodies, 0);
  planes_.clear();
  int first_body = kWorld;
  needs_sweep_ = false;
  for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
    const Collider& c = scene_.colliders[i];
    if (c.shape.type == ShapeType::kPlane) {
      planes_.push_back(static_cast<int>(i));
      continue;
    }
    if (c.body == kWorld || (first_body != kWorld && c.body != first_body)) needs_sweep_ = true;
    if (first_body == kWorld) first_body = c.body;
  }
  // static colliders have their pose once and for all
  collider_pose_.assign(scene_.colliders.size(), Eigen::Isometry3d::Identity());
  collider_rotated_.resize(scene_.colliders.size());
  bounding_radius_.resize(scene_.colliders.size());
  for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
    collider_rotated_[i] = !scene_.colliders[i].pose.linear().isIdentity(0.0);
    // padded by the hysteresis of the index set (12): the broad phase must pass a pair whose
    // contact was closed and now has a round-off-level positive gap (a sphere's bounding sphere
    // is the sphere itself: unpadded, the pair was dropped before the narrow phase saw it)
    bounding_radius_[i] = BoundingRadius(scene_.colliders[i].shape) + kContactHysteresis;
  }
  for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
    if (scene_.colliders[i].body == kWorld) collider_pose_[i] = scene_.colliders[i].pose;
  }
  spheres_.clear();
  spheres_.reserve(scene_.colliders.size());
  pairs_.reserve(2 * scene_.colliders.size());
  merged_pairs_.reserve(2 * scene_.colliders.size());
  closed_.reserve(2 * scene_.colliders.size());
  closed_count_ = 0;
  contacts_.reserve(2 * scene_.colliders.size());
  memory_.reserve(4 * scene_.colliders.size());
}

StepStatistics Simulator::Step() {
  StepStatistics stats;
  Step(&stats);
  return stats;
}

void Simulator::Step(StepStatistics* out) {
  StepStatistics& stats = *out;
  stats.solver.iterations = 0;
  stats.solver.residual = 0.0;
  stats.solver.max_change = 0.0;
  stats.solver.converged = true;
  stats.closed_contacts = 0;
  stats.islands = 0;
  stats.max_penetration = 0.0;
  stats.gyroscopic_passes = 0;
  stats.max_dt_omega = 0.0;
  stats.explicit_gyroscopic_unsafe = false;
  stats.gap_correction = 0.0;
  stats.gap_correction_energy = 0.0;
  stats.gap_correction_undone = false;
  stats.energy = std::numeric_limits<double>::quiet_NaN();
  stats.state_finite = !diverged_;
  if (diverged_) return;

  bool finite = true;
  ComputeMidpoints(&stats, &finite);
  if (!finite) {
    diverged_ = true;
    stats.state_finite = false;
    return;
  }
  // (12) the index set at q_M, and the islands of bodies it links
  FindContacts(&stats);
  BuildIslands(&stats);
  // every closed contact belongs to an island, whose solve writes its flags
  if (stats.solver.friction_projected.size() != closed_count_) {
    stats.solver.friction_projected.resize(closed_count_);
    stats.solver.normal_projected.resize(closed_count_);
  }
  for (const Island& island : islands_) {
    finite = finite && SolveIsland(island, &stats);
  }
  if (implicit_step_) {
    // bodies without contact: the implicit midpoint rule alone, torque-free
    for (std::size_t b = 0; b < state_.size(); ++b) {
      BodyStep& w = body_step_[b];
      if (w.island >= 0) continue;
      // torque-free unless an external torque acts (its impulse in K, ComputeMidpoints)
      const Eigen::Vector3d impulse =
          w.external ? w.angular_external : Eigen::Vector3d(Eigen::Vector3d::Zero());
      w.angular_end = ImplicitMidpointEuler(inertia_[b], state_[b].angular_velocity, impulse,
                                            options_.time_step, w.angular_free);
    }
  }
  finite = finite && ComputeEndState();
  // the end state's energy, summed as Energy() sums it: a state whose energy overflows is as lost
  // as one with an inf (ComputeEndState checks |v|² and |ω|², not m, Θ and g·r_S)
  double energy = 0.0;
  for (std::size_t b = 0; finite && b < state_.size(); ++b) {
    const BodyStep& w = body_step_[b];
    energy += BodyEnergy(scene_.bodies[b], scene_.gravity, w.position_end, w.linear_end,
                         w.angular_end);
  }
  if (!finite || !std::isfinite(energy)) {
    // the step is not taken: state, time and contact report stay as they were (SetState clears
    // the warm start this step may have written)
    diverged_ = true;
    stats.state_finite = false;
    return;
  }
  for (std::size_t b = 0; b < state_.size(); ++b) {
    BodyState& s = state_[b];
    const BodyStep& w = body_step_[b];
    s.linear_velocity = w.linear_end;
    s.angular_velocity = w.angular_end;
    s.position = w.position_end;
    s.orientation = w.orientation_end;
  }
  time_ += options_.time_step;
  if (options_.gap_correction) {
    gap_moved_ = false;
    CorrectGaps(&stats);
    // CorrectGaps runs after the checks above: a correction that made anything non-finite (a body
    // set far beyond every scale, e.g. 1e300 m deep: NaN rotations, lifts whose norm or energy
    // overflows) is undone, back to the end state checked above, which body_step_ still holds
    // (CorrectGaps moves state_ only, so this costs no copy and no allocation); checked only if
    // it moved a body
    bool corrected_finite =
        !gap_moved_ ||
        (std::isfinite(stats.gap_correction) && std::isfinite(stats.gap_correction_energy));
    const double end_energy = energy;
    energy = 0.0;
    for (std::size_t b = 0; gap_moved_ && corrected_finite && b < state_.size(); ++b) {
      const BodyState& s = state_[b];
      corrected_finite = AllFinite(s.position) && AllFinite(s.orientation.coeffs());
      energy += BodyEnergy(scene_.bodies[b], scene_.gravity, s.position, s.linear_velocity,
                           s.angular_velocity);
    }
    if (!corrected_finite || !std::isfinite(energy)) {
      for (std::size_t b = 0; b < state_.size(); ++b) {
        state_[b].position = body_step_[b].position_end;
        state_[b].orientation = body_step_[b].orientation_end;
      }
      stats.gap_correction = 0.0;
      stats.gap_correction_energy = 0.0;
      stats.gap_correction_undone = true;
      energy = end_energy;
    } else if (!gap_moved_) {
      energy = end_energy;
    }
  }
  stats.energy = energy;
  // the report: γ_E = W(q_M)ᵀu_E, the velocity the contact law constrained
  contacts_.resize(closed_count_);
  for (std::size_t i = 0; i < closed_count_; ++i) {
    ClosedContact& c = closed_[i];
    c.report.relative_velocity.setZero();
    for (const ContactSide& side : c.jacobian.side) {
      if (side.body < 0) continue;
      const BodyState& s = state_[static_cast<std::size_t>(side.body)];
      c.report.relative_velocity +=
          SideVelocity(c.jacobian, side, s.linear_velocity, s.angular_velocity);
    }
    contacts_[i] = c.report;
  }
  ++step_count_;
}

void Simulator::ComputeMidpoints(StepStatistics* stats, bool* finite) {
  const double dt = options_.time_step;
  const double half_dt = 0.5 * dt;
  // (13) q_M = q_B + Δt/2 F(q_B) u_B, and u_B + M⁻¹ h(q_M, u_B) Δt (14)
  double max_omega_sq = 0.0;  // max |ω|²: one square root per step, the same rounded maximum
  for (std::size_t b = 0; b < state_.size(); ++b) {
    const BodyState& s = state_[b];
    const BodyInertia& body = inertia_[b];
    BodyStep& w = body_step_[b];
    w.position_mid = s.position + half_dt * s.linear_velocity;
    w.orientation_mid = AdvanceOrientation(s.orientation, s.angular_velocity, half_dt).normalized();
    w.rotation_mid = w.orientation_mid.toRotationMatrix();
    w.linear_free = s.linear_velocity + dt * scene_.gravity;
    w.gyroscopic_impulse = dt * GyroscopicTorque(body, s.angular_velocity);
    w.angular_free = s.angular_velocity + InverseInertiaTimes(body, w.gyroscopic_impulse);
    // the external wrench enters h(q_M, u_B) with gravity: v += Δt F/m, ω += Θ⁻¹ Δt A(p_M)ᵀτ
    // (A(p_B) would be first order in the torque's turning); skipped without one, so that a world
    // without wrenches steps exactly as before
    w.external = any_wrench_ && wrench_[b].set;
    if (w.external) {
      w.linear_free += (dt * body.inverse_mass) * wrench_[b].force;
      w.angular_external = dt * (w.rotation_mid.transpose() * wrench_[b].torque);
      w.angular_free += InverseInertiaTimes(body, w.angular_external);
    }
    w.angular_end = w.angular_free;
    w.linear_contact.setZero();
    w.angular_contact.setZero();
    w.island = -1;
    max_omega_sq = std::max(max_omega_sq, s.angular_velocity.squaredNorm());
    *finite = *finite &&
              MidpointIsFinite(w.position_mid, w.orientation_mid, w.linear_free, w.angular_free);
  }
  stats->max_dt_omega = std::max(stats->max_dt_omega, dt * std::sqrt(max_omega_sq));
  const bool beyond = stats->max_dt_omega > kExplicitGyroscopicMaxDtOmega;
  implicit_step_ = options_.gyroscopic == GyroscopicScheme::kImplicitMidpoint ||
                   (options_.gyroscopic == GyroscopicScheme::kAuto && beyond);
  stats->explicit_gyroscopic_unsafe = !implicit_step_ && beyond;
}

bool Simulator::ComputeEndState() {
  const double half_dt = 0.5 * options_.time_step;
  bool finite = true;
  // (18) u_E, then (15) q_E = q_M + Δt/2 F(q_M) u_E with the quaternion renormalised
  for (std::size_t b = 0; b < state_.size(); ++b) {
    BodyStep& w = body_step_[b];
    w.linear_end = w.linear_free + inertia_[b].inverse_mass * w.linear_contact;
    w.position_end = w.position_mid + half_dt * w.linear_end;
    w.orientation_end = AdvanceOrientation(w.orientation_mid, w.angular_end, half_dt).normalized();
    w.rotation_end = w.orientation_end.toRotationMatrix();
    // the squared norms too: a state whose energy overflows is as lost as one with an inf
    finite = finite && std::isfinite(w.linear_end.squaredNorm()) &&
             std::isfinite(w.angular_end.squaredNorm()) && AllFinite(w.position_end) &&
             AllFinite(w.orientation_end.coeffs());
  }
  return finite;
}

const ContactState* Simulator::FindContact(int collider) const {
  for (const ContactState& c : contacts_) {
    if (c.collider_a == collider || c.collider_b == collider) return &c;
  }
  return nullptr;
}

void Simulator::SetState(const std::vector<BodyState>& state) {
  ValidateState(scene_, state);
  RequireFiniteEnergy(scene_, state);
  state_ = Normalized(state);
  diverged_ = false;
  memory_.clear();
  contacts_.clear();
}

void Simulator::RequireFiniteEnergy(const Scene& scene, const std::vector<BodyState>& state) {
  // the terms as MechanicalEnergy computes them (and |v|², |ω|², which a step checks); the bounds
  // named are those of these operations
  constexpr double kMax = std::numeric_limits<double>::max();
  auto reject = [](std::size_t b, const char* field, const std::string& what) {
    std::ostringstream message;
    message << "state[" << b << "]." << field << ": " << what;
    throw std::invalid_argument(message.str());
  };
  double energy = 0.0;
  for (std::size_t b = 0; b < state.size(); ++b) {
    const RigidBody& body = scene.bodies[b];
    const BodyState& s = state[b];
    const double linear = 0.5 * body.mass * s.linear_velocity.squaredNorm();
    const double angular = 0.5 * s.angular_velocity.dot(body.inertia * s.angular_velocity);
    const double potential = body.mass * scene.gravity.dot(s.position);
    std::ostringstream range;
    range.precision(3);
    if (!std::isfinite(linear)) {
      range << "the kinetic energy ½m|v_S|² overflows; |v_S| must be below "
            << std::sqrt(kMax / std::max(1.0, 0.5 * body.mass)) << " m/s";
      reject(b, "linear_velocity", range.str());
    }
    // |ω|² too, as the step checks it (with a small Θ, ½ωᵀΘω can be finite where |ω|² is not)
    if (!std::isfinite(angular) || !std::isfinite(s.angular_velocity.squaredNorm())) {
      const double largest = body.inertia.cwiseAbs().rowwise().sum().maxCoeff();
      range << "the kinetic energy ½ωᵀΘω overflows; |ω| must be below about "
            << std::sqrt(kMax / std::max(1.0, largest)) << " rad/s";
      reject(b, "angular_velocity", range.str());
    }
    if (!std::isfinite(potential)) {
      range << "the potential energy -m g·r_S overflows; |r_S| along g must be below "
            << kMax / (std::max(1.0, body.mass) * scene.gravity.norm()) << " m";
      reject(b, "position", range.str());
    }
    energy += BodyEnergy(body, scene.gravity, s.position, s.linear_velocity, s.angular_velocity);
    if (!std::isfinite(energy)) {
      range << "state: the mechanical energy Σ ½m|v_S|² + ½ωᵀΘω - m g·r_S overflows at state["
            << b << "] (each body's terms are finite, their sum is not); it must stay below "
            << kMax << " J in magnitude";
      throw std::invalid_argument(range.str());
    }
  }
}

void Simulator::SetTime(double time) {
  if (!std::isfinite(time)) throw std::invalid_argument("time must be finite [s]");
  time_ = time;
}

void Simulator::SetOptions(const SimulatorOptions& options) {
  ValidateSimulatorOptions(options);
  // percussions scale with Δt: a warm start from another step size would be off by the ratio
  if (options.time_step != options_.time_step) {
    for (auto& [key, memory] : memory_) memory.DropWarmStart();
  }
  options_ = options;
}

ContactLaw Simulator::PairLaw(int first, int second) const {
  ContactLaw law = CombineLaws(scene_.colliders[static_cast<std::size_t>(first)],
                               scene_.colliders[static_cast<std::size_t>(second)]);
  for (const auto& [pair, set] : pair_sets_) {  // usually empty
    if (pair.first == first && pair.second == second) law.friction_set = set;
  }
  return law;
}

FrictionSet Simulator::FrictionSetOf(const std::string& name) const {
  const int collider = FindCollider(scene_, name);
  if (collider >= 0) return scene_.colliders[static_cast<std::size_t>(collider)].law.friction_set;
  const std::size_t slash = name.find('/');
  const int first = slash == std::string::npos ? -1 : FindCollider(scene_, name.substr(0, slash));
  const int second = slash == std::string::npos ? -1 : FindCollider(scene_, name.substr(slash + 1));
  if (first < 0 || second < 0 || first == second) {
    throw std::invalid_argument("unknown contact \"" + name +
                                "\": expected a collider name or \"<collider>/<collider>\"");
  }
  return PairLaw(std::min(first, second), std::max(first, second)).friction_set;
}

void Simulator::SetFrictionSet(FrictionSet set, const std::string& name) {
  if (FrictionSetName(set) == "unknown") {
    throw std::invalid_argument("friction set must be one of " + FrictionSetNameList());
  }
  if (name.empty()) {
    for (Collider& c : scene_.colliders) c.law.friction_set = set;
    pair_sets_.clear();
  } else if (const int collider = FindCollider(scene_, name); collider >= 0) {
    scene_.colliders[static_cast<std::size_t>(collider)].law.friction_set = set;
    pair_sets_.erase(std::remove_if(pair_sets_.begin(), pair_sets_.end(),
                                    [collider](const auto& entry) {
                                      return entry.first.first == collider ||
                                             entry.first.second == collider;
                                    }),
                     pair_sets_.end());
  } else {
    FrictionSetOf(name);  // throws for an unknown name
    const std::size_t slash = name.find('/');
    const int a = FindCollider(scene_, name.substr(0, slash));
    const int b = FindCollider(scene_, name.substr(slash + 1));
    const std::pair<int, int> pair(std::min(a, b), std::max(a, b));
    bool found = false;
    for (auto& [p, s] : pair_sets_) {
      if (p == pair) {
        s = set;
        found = true;
      }
    }
    if (!found) pair_sets_.emplace_back(pair, set);
  }
  // the warm start of a contact whose set changed would start outside its new set
  for (auto& [key, memory] : memory_) memory.DropWarmStart();
}

void Simulator::SetContactLaw(int collider, const ContactLaw& law) {
  const int count = static_cast<int>(scene_.colliders.size());
  if (collider < 0 || collider >= count) {
    throw std::out_of_range("collider index " + std::to_string(collider) + " not in [0, " +
                            std::to_string(count) + ")");
  }
  ValidateLaw("law of collider " + scene_.colliders[static_cast<std::size_t>(collider)].name, law);
  scene_.colliders[static_cast<std::size_t>(collider)].law = law;
  for (auto& [key, memory] : memory_) memory.DropWarmStart();
}

}  // namespace nonsmooth_sim
