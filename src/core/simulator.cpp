// Moreau midpoint time-stepping (13)-(18), see simulator.h.
#include "nonsmooth_sim/core/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace nonsmooth_sim {
namespace {

constexpr double kMinTimeStep = 1e-7;  // [s]
constexpr double kMaxTimeStep = 1e-2;  // [s]
// The implicit-midpoint passes stop once ω_E changes by less than this relative amount even when
// the solver tolerance is tighter: below it the change is round-off.
constexpr double kGyroscopicRoundOff = 4.0 * std::numeric_limits<double>::epsilon();

std::vector<BodyState> Normalized(std::vector<BodyState> state) {
  for (BodyState& s : state) s.orientation.normalize();
  return state;
}

// What (13) and the free velocities produced from one body's q_B, u_B.
bool MidpointIsFinite(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                      const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  return position.allFinite() && orientation.coeffs().allFinite() && linear.allFinite() &&
         angular.allFinite();
}

}  // namespace

void ValidateSimulatorOptions(const SimulatorOptions& options) {
  if (!(options.time_step >= kMinTimeStep && options.time_step <= kMaxTimeStep)) {
    std::ostringstream s;
    s << "SimulatorOptions.time_step = " << options.time_step << ": must be in [" << kMinTimeStep
      << ", " << kMaxTimeStep << "] s";
    throw std::invalid_argument(s.str());
  }
  ValidateSolverOptions(options.solver);
  if (GyroscopicSchemeName(options.gyroscopic) == "unknown") {
    throw std::invalid_argument(
        "SimulatorOptions.gyroscopic must be kExplicit or kImplicitMidpoint");
  }
}

Simulator::Simulator(Scene scene, SimulatorOptions options)
    : scene_(std::move(scene)), options_(options) {
  ValidateScene(scene_);
  ValidateSimulatorOptions(options_);
  state_ = Normalized(scene_.initial_state);
  Initialize();
}

void Simulator::Initialize() {
  const std::size_t bodies = scene_.bodies.size();
  const std::size_t spheres = scene_.spheres.size();
  inertia_.clear();
  for (const RigidBody& body : scene_.bodies) {
    inertia_.push_back(MakeBodyInertia(body.mass, body.inertia));
  }
  body_step_.assign(bodies, BodyStep{});
  closed_.clear();
  closed_.reserve(spheres);
  dimension_.assign(spheres, 0);
  for (std::size_t i = 0; i < spheres; ++i) dimension_[i] = ContactDimension(scene_.spheres[i].law);
  warm_start_.assign(spheres, Eigen::Vector4d::Zero());
  contacts_.assign(spheres, ContactState{});
  // sizes n = 0 ... 4·spheres; each problem is allocated when its size first occurs
  problems_.resize(4 * spheres + 1);
  lambdas_.resize(4 * spheres + 1);
}

ContactProblem& Simulator::ProblemOfSize(int size) {
  ContactProblem& problem = problems_[static_cast<std::size_t>(size)];
  if (problem.G.rows() != size) {
    problem.G.setZero(size, size);
    problem.c.setZero(size);
    problem.contacts.reserve(scene_.spheres.size());
    lambdas_[static_cast<std::size_t>(size)].setZero(size);
  }
  return problem;
}

StepStatistics Simulator::Step() {
  StepStatistics stats;
  Step(&stats);
  return stats;
}

void Simulator::Step(StepStatistics* out) {
  const double dt = options_.time_step;
  const double half_dt = 0.5 * dt;
  StepStatistics& stats = *out;
  stats.solver.iterations = 0;
  stats.solver.residual = 0.0;
  stats.solver.max_change = 0.0;
  stats.solver.converged = true;
  stats.closed_contacts = 0;
  stats.gyroscopic_passes = 0;
  stats.max_dt_omega = 0.0;
  stats.explicit_gyroscopic_unsafe = false;
  stats.gap_correction = 0.0;
  stats.gap_correction_energy = 0.0;
  stats.state_finite = !diverged_;
  if (diverged_) return;

  // (13) q_M = q_B + Δt/2 F(q_B) u_B, and u_B + M⁻¹ h(q_M, u_B) Δt (14)
  bool finite = true;
  for (std::size_t b = 0; b < state_.size(); ++b) {
    const BodyState& s = state_[b];
    const BodyInertia& body = inertia_[b];
    BodyStep& w = body_step_[b];
    w.position_mid = s.position + half_dt * s.linear_velocity;
    w.orientation_mid = AdvanceOrientation(s.orientation, s.angular_velocity, half_dt).normalized();
    w.rotation_mid = w.orientation_mid.toRotationMatrix();
    w.linear_free = s.linear_velocity + dt * scene_.gravity;
    w.gyroscopic_impulse = dt * GyroscopicTorque(body.inertia, s.angular_velocity);
    w.angular_free = s.angular_velocity + body.inverse_inertia * w.gyroscopic_impulse;
    w.angular_end = w.angular_free;
    w.linear_contact.setZero();
    w.angular_contact.setZero();
    w.has_contact = false;
    stats.max_dt_omega = std::max(stats.max_dt_omega, dt * s.angular_velocity.norm());
    finite = finite &&
             MidpointIsFinite(w.position_mid, w.orientation_mid, w.linear_free, w.angular_free);
  }
  stats.explicit_gyroscopic_unsafe = options_.gyroscopic == GyroscopicScheme::kExplicit &&
                                     stats.max_dt_omega > kExplicitGyroscopicMaxDtOmega;
  if (!finite) {
    diverged_ = true;
    stats.state_finite = false;
    return;
  }

  // (12) index set at the midpoint: g_i(q_M) ≤ 0
  closed_.clear();
  int size = 0;
  for (std::size_t i = 0; i < scene_.spheres.size(); ++i) {
    const Sphere& sphere = scene_.spheres[i];
    BodyStep& w = body_step_[static_cast<std::size_t>(sphere.body)];
    if (SphereGroundGap(w.position_mid, w.rotation_mid, sphere.center, sphere.radius) > 0.0) {
      continue;
    }
    ClosedContact& contact = closed_.emplace_back();
    contact.sphere = static_cast<int>(i);
    contact.body = sphere.body;
    contact.offset = size;
    contact.dimension = dimension_[i];
    contact.kinematics =
        SphereGroundKinematics(w.position_mid, w.rotation_mid, sphere.center, sphere.radius);
    const BodyState& s = state_[static_cast<std::size_t>(sphere.body)];
    contact.gamma_begin =
        ContactVelocity(contact.kinematics, s.linear_velocity, s.angular_velocity);
    w.has_contact = true;
    size += contact.dimension;
  }
  stats.closed_contacts = static_cast<int>(closed_.size());

  if (size > 0) {
    finite = SolveContacts(size, &stats);
  } else {
    stats.solver.friction_projected.clear();
    stats.solver.normal_projected.clear();
  }
  if (size == 0 && options_.gyroscopic == GyroscopicScheme::kImplicitMidpoint) {
    // torque-free: the implicit midpoint rule alone
    for (std::size_t b = 0; b < state_.size(); ++b) {
      BodyStep& w = body_step_[b];
      w.angular_end = ImplicitMidpointEuler(inertia_[b], state_[b].angular_velocity,
                                            Eigen::Vector3d::Zero(), dt, w.angular_free);
    }
  }
  if (!finite || !ComputeEndState()) {
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
  time_ += dt;
  if (options_.gap_correction) CorrectGaps(&stats);
  ReportContacts();
}

bool Simulator::ComputeEndState() {
  const double half_dt = 0.5 * options_.time_step;
  bool finite = true;
  // (18) u_E, then (15) q_E = q_M + Δt/2 F(q_M) u_E with the quaternion renormalised
  for (std::size_t b = 0; b < state_.size(); ++b) {
    BodyStep& w = body_step_[b];
    w.linear_end = w.linear_free + inertia_[b].inverse_mass * w.linear_contact;
    w.position_end = w.position_mid + half_dt * w.linear_end;
    w.orientation_end =
        AdvanceOrientation(w.orientation_mid, w.angular_end, half_dt).normalized();
    w.rotation_end = w.orientation_end.toRotationMatrix();
    // the squared norms too: a state whose energy overflows is as lost as one with an inf
    finite = finite && std::isfinite(w.linear_end.squaredNorm()) &&
             std::isfinite(w.angular_end.squaredNorm()) && w.position_end.allFinite() &&
             w.orientation_end.coeffs().allFinite();
  }
  return finite;
}

void Simulator::CorrectGaps(StepStatistics* stats) {
  // the highest end gap g(q_E) of each body's closed contacts (12): lifting by its depth (less the
  // slop) leaves every contact that carried the body closed at ≤ -slop. Lifting by the deepest
  // one instead opens the others of a tilted body on several contacts, which then falls back:
  // measured on a block on four feet, a rocking limit cycle fed by m g Δz every other step.
  for (BodyStep& w : body_step_) w.highest_closed_gap = -std::numeric_limits<double>::infinity();
  for (const ClosedContact& a : closed_) {
    const Sphere& sphere = scene_.spheres[static_cast<std::size_t>(a.sphere)];
    BodyStep& w = body_step_[static_cast<std::size_t>(a.body)];
    const double gap =
        SphereGroundGap(w.position_end, w.rotation_end, sphere.center, sphere.radius);
    w.highest_closed_gap = std::max(w.highest_closed_gap, gap);
  }
  for (std::size_t b = 0; b < state_.size(); ++b) {
    if (!body_step_[b].has_contact) continue;
    const double depth = -body_step_[b].highest_closed_gap;
    if (!(depth > kGapCorrectionSlop)) continue;
    // lift along the ground normal +ẑ to the slop; velocities unchanged
    const double lift = depth - kGapCorrectionSlop;
    state_[b].position.z() += lift;
    stats->gap_correction = std::max(stats->gap_correction, lift);
    stats->gap_correction_energy -= inertia_[b].mass * scene_.gravity.z() * lift;
  }
}

bool Simulator::SolveContacts(int size, StepStatistics* stats) {
  const double dt = options_.time_step;
  ContactProblem& problem = ProblemOfSize(size);
  Eigen::VectorXd& lambda = lambdas_[static_cast<std::size_t>(size)];
  problem.contacts.clear();
  for (const ClosedContact& a : closed_) {
    problem.contacts.push_back(ContactBlock{a.offset, scene_.spheres[a.sphere].law});
    // warm start from the previous step's percussions (zero if the contact was open then)
    lambda.segment(a.offset, a.dimension) = warm_start_[a.sphere].head(a.dimension);
  }

  // (16) G_ij = W_iᵀ M⁻¹ W_j; contacts on different bodies do not couple (fixed ground)
  for (std::size_t i = 0; i < closed_.size(); ++i) {
    const ClosedContact& a = closed_[i];
    for (std::size_t j = i; j < closed_.size(); ++j) {
      const ClosedContact& b = closed_[j];
      if (a.body != b.body) {
        problem.G.block(a.offset, b.offset, a.dimension, b.dimension).setZero();
        problem.G.block(b.offset, a.offset, b.dimension, a.dimension).setZero();
        continue;
      }
      const Eigen::Matrix4d block =
          DelassusBlock(inertia_[static_cast<std::size_t>(a.body)], a.kinematics, b.kinematics);
      if (a.dimension == 4 && b.dimension == 4) {
        problem.G.block<4, 4>(a.offset, b.offset) = block;
        if (j != i) problem.G.block<4, 4>(b.offset, a.offset) = block.transpose();
        continue;
      }
      problem.G.block(a.offset, b.offset, a.dimension, b.dimension) =
          block.topLeftCorner(a.dimension, b.dimension);
      if (j != i) {
        problem.G.block(b.offset, a.offset, b.dimension, a.dimension) =
            block.topLeftCorner(a.dimension, b.dimension).transpose();
      }
    }
  }

  const bool implicit = options_.gyroscopic == GyroscopicScheme::kImplicitMidpoint;
  const double pass_tolerance = std::max(options_.solver.tolerance_rel, kGyroscopicRoundOff);
  int total_iterations = 0;
  for (int pass = 0; pass < kMaxGyroscopicPasses; ++pass) {
    // (16) c_i = W_iᵀ M⁻¹ h Δt + (1 + ε_i) γ_i^B = W_iᵀ(u_B + M⁻¹hΔt) + ε_i γ_i^B
    for (const ClosedContact& a : closed_) {
      const BodyStep& w = body_step_[static_cast<std::size_t>(a.body)];
      const Eigen::Vector4d gamma_free =
          ContactVelocity(a.kinematics, w.linear_free, w.angular_free);
      const double restitution = scene_.spheres[a.sphere].law.restitution;
      problem.c.segment(a.offset, a.dimension) =
          (gamma_free + restitution * a.gamma_begin).head(a.dimension);
    }
    // a diverged state (huge ω) can overflow c; the solver would reject it
    if (!problem.c.allFinite()) return false;
    // (17)
    solver_.Solve(problem, options_.solver, &lambda, &stats->solver);
    total_iterations += stats->solver.iterations;
    stats->gyroscopic_passes = pass + 1;

    // (18) the contact part M⁻¹ Σ W_i Λ_i, per body
    for (BodyStep& w : body_step_) {
      w.linear_contact.setZero();
      w.angular_contact.setZero();
    }
    for (const ClosedContact& a : closed_) {
      BodyStep& w = body_step_[static_cast<std::size_t>(a.body)];
      Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
      percussion.head(a.dimension) = lambda.segment(a.offset, a.dimension);
      w.linear_contact += ContactLinearImpulse(percussion);
      w.angular_contact += ContactAngularImpulse(a.kinematics, percussion);
    }
    if (!implicit) {
      for (std::size_t b = 0; b < body_step_.size(); ++b) {
        BodyStep& w = body_step_[b];
        w.angular_end = w.angular_free + inertia_[b].inverse_inertia * w.angular_contact;
      }
      break;
    }

    // implicit midpoint on Euler's equations for the current Λ; its gyroscopic impulse enters c
    // of the next pass
    bool settled = true;
    for (std::size_t b = 0; b < body_step_.size(); ++b) {
      BodyStep& w = body_step_[b];
      const BodyInertia& body = inertia_[b];
      const Eigen::Vector3d& omega_begin = state_[b].angular_velocity;
      if (!w.has_contact) {
        // torque-free: nothing couples it to the passes, one solve suffices
        if (pass == 0) {
          w.angular_end = ImplicitMidpointEuler(body, omega_begin, Eigen::Vector3d::Zero(), dt,
                                                w.angular_free);
        }
        continue;
      }
      const Eigen::Vector3d guess =
          pass == 0 ? Eigen::Vector3d(w.angular_free + body.inverse_inertia * w.angular_contact)
                    : w.angular_end;
      const Eigen::Vector3d omega_end =
          ImplicitMidpointEuler(body, omega_begin, w.angular_contact, dt, guess);
      if ((omega_end - guess).norm() > pass_tolerance * omega_end.norm()) settled = false;
      w.angular_end = omega_end;
      // the gyroscopic impulse -Δt ω_M × Θω_M that this ω_E balances
      w.gyroscopic_impulse = body.inertia * (omega_end - omega_begin) - w.angular_contact;
      w.angular_free = omega_begin + body.inverse_inertia * w.gyroscopic_impulse;
    }
    if (settled) break;
  }
  stats->solver.iterations = total_iterations;

  // warm start of the next step: this step's percussions, zero for contacts that were open
  for (Eigen::Vector4d& w : warm_start_) w.setZero();
  for (const ClosedContact& a : closed_) {
    warm_start_[a.sphere].head(a.dimension) = lambda.segment(a.offset, a.dimension);
  }
  return true;
}

void Simulator::ReportContacts() {
  std::size_t next_closed = 0;
  for (std::size_t i = 0; i < scene_.spheres.size(); ++i) {
    const Sphere& sphere = scene_.spheres[i];
    const BodyState& s = state_[static_cast<std::size_t>(sphere.body)];
    const Eigen::Matrix3d& rotation =
        body_step_[static_cast<std::size_t>(sphere.body)].rotation_end;
    ContactState& report = contacts_[i];
    // P = r_S + A K_r_SM - ρẑ at q_E; g = P·ẑ
    Eigen::Vector3d r_sp_world = rotation * sphere.center;
    r_sp_world.z() -= sphere.radius;
    report.point = s.position + r_sp_world;
    report.gap = report.point.z();
    report.closed =
        next_closed < closed_.size() && closed_[next_closed].sphere == static_cast<int>(i);
    if (report.closed) {
      // γ_E = W(q_M)ᵀu_E, the velocity the contact law constrained
      const ClosedContact& a = closed_[next_closed++];
      report.percussion = warm_start_[i];
      report.relative_velocity =
          ContactVelocity(a.kinematics, s.linear_velocity, s.angular_velocity);
    } else {
      // W(q_E)ᵀu_E: velocity of P in world x, y, z and the spin about ẑ
      const Eigen::Vector3d omega_world = rotation * s.angular_velocity;
      const Eigen::Vector3d v_p = s.linear_velocity + omega_world.cross(r_sp_world);
      report.percussion.setZero();
      report.relative_velocity = Eigen::Vector4d(v_p.z(), v_p.x(), v_p.y(), omega_world.z());
    }
  }
  // open contacts carry no warm start
  if (closed_.empty()) {
    for (Eigen::Vector4d& w : warm_start_) w.setZero();
  }
}

void Simulator::SetState(const std::vector<BodyState>& state) {
  ValidateState(scene_, state);
  state_ = Normalized(state);
  diverged_ = false;
  for (Eigen::Vector4d& w : warm_start_) w.setZero();
  contacts_.assign(scene_.spheres.size(), ContactState{});
}

void Simulator::SetTime(double time) {
  if (!std::isfinite(time)) throw std::invalid_argument("time must be finite [s]");
  time_ = time;
}

void Simulator::SetOptions(const SimulatorOptions& options) {
  ValidateSimulatorOptions(options);
  // percussions scale with Δt: a warm start from another step size would be off by the ratio
  if (options.time_step != options_.time_step) {
    for (Eigen::Vector4d& w : warm_start_) w.setZero();
  }
  options_ = options;
}

void Simulator::SetFrictionSet(FrictionSet set, std::optional<int> sphere) {
  const int count = static_cast<int>(scene_.spheres.size());
  if (sphere && (*sphere < 0 || *sphere >= count)) {
    throw std::out_of_range("sphere index " + std::to_string(*sphere) + " not in [0, " +
                            std::to_string(count) + ")");
  }
  if (FrictionSetName(set) == "unknown") {
    throw std::invalid_argument("friction set must be one of " + FrictionSetNameList());
  }
  for (int i = 0; i < count; ++i) {
    if (sphere && *sphere != i) continue;
    ContactLaw& law = scene_.spheres[static_cast<std::size_t>(i)].law;
    if (law.friction_set == set) continue;
    law.friction_set = set;
    dimension_[static_cast<std::size_t>(i)] = ContactDimension(law);
    warm_start_[static_cast<std::size_t>(i)].setZero();
  }
}

void Simulator::SetContactLaw(int sphere, const ContactLaw& law) {
  const int count = static_cast<int>(scene_.spheres.size());
  if (sphere < 0 || sphere >= count) {
    throw std::out_of_range("sphere index " + std::to_string(sphere) + " not in [0, " +
                            std::to_string(count) + ")");
  }
  Scene candidate = scene_;
  candidate.spheres[static_cast<std::size_t>(sphere)].law = law;
  candidate.initial_state = state_;
  ValidateScene(candidate);
  scene_.spheres[static_cast<std::size_t>(sphere)].law = law;
  dimension_[static_cast<std::size_t>(sphere)] = ContactDimension(law);
  warm_start_[static_cast<std::size_t>(sphere)].setZero();
}

}  // namespace nonsmooth_sim
