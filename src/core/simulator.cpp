// Moreau midpoint time-stepping (13)-(18), see simulator.h: the step as an orchestration of the
// stages of core/step/, and the setters. The world's changes are in simulator_world.cpp.
#include "nonsmooth_sim/core/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "nonsmooth_sim/core/all_finite.h"
#include "nonsmooth_sim/core/step/moreau_kinematics.h"

namespace nonsmooth_sim {
namespace {

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

// The two colliders of a contact name "<collider>/<collider>": the split at a '/' where both
// halves are colliders (names of spawned models hold a '/' themselves: "m/a/m/b"); {-1, -1} if
// none or the same collider twice.
std::pair<int, int> ContactColliders(const Scene& scene, const std::string& name) {
  for (std::size_t slash = name.find('/'); slash != std::string::npos;
       slash = name.find('/', slash + 1)) {
    const int first = FindCollider(scene, name.substr(0, slash));
    const int second = first < 0 ? -1 : FindCollider(scene, name.substr(slash + 1));
    if (first >= 0 && second >= 0 && first != second) return {first, second};
  }
  return {-1, -1};
}

}  // namespace

Simulator::Simulator(Scene scene, SimulatorOptions options) : options_(options) {
  model_.scene = std::move(scene);
  ValidateScene(model_.scene);
  ValidateSimulatorOptions(options_);
  RequireFiniteEnergy(model_.scene, model_.scene.initial_state);
  state_ = Normalized(model_.scene.initial_state);
  Initialize();
}

void Simulator::Initialize() {
  BuildCaches();
  data_.memory.clear();
  contacts_.clear();
  model_.wrench.assign(model_.scene.bodies.size(), BodyWrench{});
  model_.any_wrench = false;
}

void Simulator::BuildCaches() {
  model_.BuildCaches();
  data_.Resize(model_);
  contact_pipeline_.Resize(model_);
  islands_.Resize(model_.scene.bodies.size());
  contacts_.reserve(2 * model_.scene.colliders.size());
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
  stats.new_contact_depth = 0.0;
  stats.gap_correction = 0.0;
  stats.gap_correction_energy = 0.0;
  stats.gap_correction_undone = false;
  stats.energy = std::numeric_limits<double>::quiet_NaN();
  stats.state_finite = !diverged_;
  if (diverged_) return;

  // (13) q_M and the free velocities of (14)
  data_.second_order = options_.integrator == Integrator::kMoreau2;
  bool finite = true;
  ComputeMidpoints(model_, options_, state_, &data_, &stats, &finite);
  if (!finite) {
    diverged_ = true;
    stats.state_finite = false;
    return;
  }
  // (12) the index set at q_M with W, and the islands of bodies it links
  contact_pipeline_.FindContacts(model_, state_, &data_, &stats);
  for (std::size_t k = 0; k < data_.closed_count; ++k) {
    const ClosedContact& c = data_.closed[k];
    if (c.memory->closed_step != data_.step - 1) {
      stats.new_contact_depth = std::max(stats.new_contact_depth, -c.report.gap);
    }
  }
  islands_.Build(data_.closed.data(), data_.closed_count);
  stats.islands = static_cast<int>(islands_.islands().size());
  // (16), (17) per island; every closed contact belongs to an island, whose solve writes its flags
  if (stats.solver.friction_projected.size() != data_.closed_count) {
    stats.solver.friction_projected.resize(data_.closed_count);
    stats.solver.normal_projected.resize(data_.closed_count);
  }
  for (std::size_t k = 0; k < islands_.islands().size(); ++k) {
    finite = finite && island_problem_.Solve(model_, options_, state_, islands_, k, &data_, &stats);
  }
  // bodies without contact: the implicit midpoint rule alone
  if (data_.implicit) SolveFreeBodiesImplicit(model_, options_, state_, islands_, &data_);
  // (18) u_E, (15) q_E
  finite = finite && ComputeEndState(model_, options_, &data_);
  // the end state's energy, summed as Energy() sums it: a state whose energy overflows is as lost
  // as one with an inf (ComputeEndState checks |v|² and |ω|², not m, Θ and g·r_S)
  const Scene& scene = model_.scene;
  double energy = 0.0;
  for (std::size_t b = 0; finite && b < state_.size(); ++b) {
    const BodyStep& w = data_.body[b];
    energy += BodyEnergy(scene.bodies[b], scene.gravity, w.position_end, w.linear_end,
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
    const BodyStep& w = data_.body[b];
    s.linear_velocity = w.linear_end;
    s.angular_velocity = w.angular_end;
    s.position = w.position_end;
    s.orientation = w.orientation_end;
  }
  time_ += options_.time_step;
  if (options_.gap_correction) {
    // the position projection after (15)
    const bool moved = position_projection_.CorrectGaps(model_, &data_, &state_, &stats);
    // it runs after the checks above: a correction that made anything non-finite (a body set far
    // beyond every scale, e.g. 1e300 m deep: NaN rotations, lifts whose norm or energy overflows)
    // is undone, back to the end state checked above, which data_.body still holds (CorrectGaps
    // moves state_ only, so this costs no copy and no allocation); checked only if it moved a
    // body
    bool corrected_finite =
        !moved ||
        (std::isfinite(stats.gap_correction) && std::isfinite(stats.gap_correction_energy));
    const double end_energy = energy;
    energy = 0.0;
    for (std::size_t b = 0; moved && corrected_finite && b < state_.size(); ++b) {
      const BodyState& s = state_[b];
      corrected_finite = AllFinite(s.position) && AllFinite(s.orientation.coeffs());
      energy += BodyEnergy(scene.bodies[b], scene.gravity, s.position, s.linear_velocity,
                           s.angular_velocity);
    }
    if (!corrected_finite || !std::isfinite(energy)) {
      for (std::size_t b = 0; b < state_.size(); ++b) {
        state_[b].position = data_.body[b].position_end;
        state_[b].orientation = data_.body[b].orientation_end;
      }
      stats.gap_correction = 0.0;
      stats.gap_correction_energy = 0.0;
      stats.gap_correction_undone = true;
      energy = end_energy;
    } else if (!moved) {
      energy = end_energy;
    }
  }
  stats.energy = energy;
  // kMoreau2: the end gaps of the closed contacts after the lift (the next step's g(q_B))
  if (data_.second_order) contact_pipeline_.RecordEndGaps(model_, state_, &data_);
  // the report: γ_E = W(q_M)ᵀu_E, the velocity the contact law constrained
  contacts_.resize(data_.closed_count);
  for (std::size_t i = 0; i < data_.closed_count; ++i) {
    ClosedContact& c = data_.closed[i];
    c.report.relative_velocity.setZero();
    for (const ContactSide& side : c.jacobian.side) {
      if (side.body < 0) continue;
      const BodyState& s = state_[static_cast<std::size_t>(side.body)];
      c.report.relative_velocity +=
          SideVelocity(c.jacobian, side, s.linear_velocity, s.angular_velocity);
    }
    contacts_[i] = c.report;
    if (data_.second_order) c.memory->gamma_end = c.report.relative_velocity;
  }
  // kMoreau2 reads the last step's γ_E and end gaps only if that step recorded them (a run
  // switched from kMoreau takes its first kMoreau2 step with every contact as a new one)
  data_.previous_time_step = data_.second_order ? options_.time_step : 0.0;
  ++data_.step;
}

const ContactState* Simulator::FindContact(int collider) const {
  for (const ContactState& c : contacts_) {
    if (c.collider_a == collider || c.collider_b == collider) return &c;
  }
  return nullptr;
}

void Simulator::SetState(const std::vector<BodyState>& state) {
  ValidateState(model_.scene, state);
  RequireFiniteEnergy(model_.scene, state);
  state_ = Normalized(state);
  diverged_ = false;
  data_.memory.clear();
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
    for (auto& [key, memory] : data_.memory) memory.DropWarmStart();
  }
  options_ = options;
}

void Simulator::SetTimeStep(double time_step) {
  SimulatorOptions options = options_;
  options.time_step = time_step;
  ValidateSimulatorOptions(options);
  const double ratio = time_step / options_.time_step;
  if (ratio != 1.0) {
    for (auto& [key, memory] : data_.memory) memory.ScaleWarmStart(ratio);
  }
  options_ = options;
}

void Simulator::Save(Checkpoint* checkpoint) const {
  Checkpoint& c = *checkpoint;
  c.state = state_;
  c.time = time_;
  c.diverged = diverged_;
  c.contacts = contacts_;
  c.memory = data_.memory;  // the copy assignment reuses the nodes the checkpoint holds
  c.step = data_.step;
  c.previous_time_step = data_.previous_time_step;
  c.time_step = options_.time_step;
}

void Simulator::Restore(const Checkpoint& checkpoint) {
  if (checkpoint.state.size() != state_.size()) {
    throw std::invalid_argument("Simulator::Restore: a checkpoint of a world with " +
                                std::to_string(checkpoint.state.size()) + " bodies, this one has " +
                                std::to_string(state_.size()));
  }
  state_ = checkpoint.state;
  time_ = checkpoint.time;
  diverged_ = checkpoint.diverged;
  contacts_ = checkpoint.contacts;
  data_.memory = checkpoint.memory;
  data_.step = checkpoint.step;
  data_.previous_time_step = checkpoint.previous_time_step;
  options_.time_step = checkpoint.time_step;
}

FrictionSet Simulator::FrictionSetOf(const std::string& name) const {
  const int collider = FindCollider(model_.scene, name);
  if (collider >= 0) return model_.scene.colliders[static_cast<std::size_t>(collider)].law.friction_set;
  const auto [first, second] = ContactColliders(model_.scene, name);
  if (first < 0) {
    throw std::invalid_argument("unknown contact \"" + name +
                                "\": expected a collider name or \"<collider>/<collider>\"");
  }
  return model_.PairLaw(std::min(first, second), std::max(first, second)).friction_set;
}

void Simulator::SetFrictionSet(FrictionSet set, const std::string& name) {
  if (!IsFrictionSet(set)) {
    throw std::invalid_argument("friction set must be one of " + FrictionSetNameList());
  }
  if (name.empty()) {
    for (Collider& c : model_.scene.colliders) c.law.friction_set = set;
    model_.pair_sets.clear();
  } else if (const int collider = FindCollider(model_.scene, name); collider >= 0) {
    model_.scene.colliders[static_cast<std::size_t>(collider)].law.friction_set = set;
    model_.pair_sets.erase(std::remove_if(model_.pair_sets.begin(), model_.pair_sets.end(),
                                    [collider](const auto& entry) {
                                      return entry.first.first == collider ||
                                             entry.first.second == collider;
                                    }),
                     model_.pair_sets.end());
  } else {
    FrictionSetOf(name);  // throws for an unknown name
    const auto [a, b] = ContactColliders(model_.scene, name);
    const std::pair<int, int> pair(std::min(a, b), std::max(a, b));
    bool found = false;
    for (auto& [p, s] : model_.pair_sets) {
      if (p == pair) {
        s = set;
        found = true;
      }
    }
    if (!found) model_.pair_sets.emplace_back(pair, set);
  }
  // the warm start of a contact whose set changed would start outside its new set
  for (auto& [key, memory] : data_.memory) memory.DropWarmStart();
}

void Simulator::SetContactLaw(int collider, const ContactLaw& law) {
  const int count = static_cast<int>(model_.scene.colliders.size());
  if (collider < 0 || collider >= count) {
    throw std::out_of_range("collider index " + std::to_string(collider) + " not in [0, " +
                            std::to_string(count) + ")");
  }
  ValidateLaw("law of collider " + model_.scene.colliders[static_cast<std::size_t>(collider)].name, law);
  model_.scene.colliders[static_cast<std::size_t>(collider)].law = law;
  for (auto& [key, memory] : data_.memory) memory.DropWarmStart();
}

}  // namespace nonsmooth_sim
