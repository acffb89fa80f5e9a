// The contact problem (17) of one island and the impulses (18) it gives, see simulator.h.
#include <algorithm>
#include <limits>

#include "nonsmooth_sim/core/all_finite.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

// The implicit-midpoint passes stop once ω_E changes by less than this relative amount even when
// the solver tolerance is tighter: below it the change is round-off.
constexpr double kGyroscopicRoundOff = 4.0 * std::numeric_limits<double>::epsilon();

// Warm starts extrapolated from a contact's last percussions Λ^{n-1}, Λ^{n-2}, Λ^{n-3}:
// linear 2Λ^{n-1} - Λ^{n-2}, quadratic 3(Λ^{n-1} - Λ^{n-2}) + Λ^{n-3}.
template <typename Memory>
Eigen::Vector4d LinearStart(const Memory& m) {
  return 2.0 * m.percussion - m.percussion_before;
}
template <typename Memory>
Eigen::Vector4d QuadraticStart(const Memory& m) {
  return 3.0 * (m.percussion - m.percussion_before) + m.percussion_before2;
}

}  // namespace

[[gnu::always_inline]] inline
Eigen::Vector4d Simulator::WarmStart(const ContactMemory& memory, bool extrapolating) const {
  // the previous step's percussion (zero if the contact was open then; the memory is zero beyond
  // the contact's dimension), or extrapolated from the last two or three
  if (memory.closed_step != step_count_ - 1) return Eigen::Vector4d::Zero();
  if (extrapolating && memory.converged && memory.closed_before == step_count_ - 2) {
    return memory.quadratic_served ? QuadraticStart(memory) : LinearStart(memory);
  }
  return memory.percussion;
}

[[gnu::always_inline]] inline
Eigen::Matrix4d Simulator::DelassusBlock(const ClosedContact& a, const ClosedContact& b) const {
  // (16) G_ij = W_iᵀ M⁻¹ W_j over the sides the two contacts share a body on
  Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
  for (const ContactSide& s : a.jacobian.side) {
    if (s.body < 0) continue;
    const BodyInertia& body = inertia_[static_cast<std::size_t>(s.body)];
    for (const ContactSide& t : b.jacobian.side) {
      if (t.body != s.body) continue;
      block += &s == &t ? OwnDelassusBlock(body, s)
                        : SideDelassusBlock(body, a.jacobian, s, b.jacobian, t);
    }
  }
  return block;
}

[[gnu::always_inline]] inline
Eigen::Vector4d Simulator::FreeContactVelocity(const ClosedContact& c) const {
  // (16) c_i = W_iᵀ M⁻¹ h Δt + (1 + ε_i) γ_i^B = W_iᵀ(u_B + M⁻¹hΔt) + ε_i γ_i^B
  Eigen::Vector4d gamma_free = Eigen::Vector4d::Zero();
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const BodyStep& w = body_step_[static_cast<std::size_t>(side.body)];
    gamma_free += SideVelocity(c.jacobian, side, w.linear_free, w.angular_free);
  }
  return gamma_free + c.report.law.restitution * c.gamma_begin;
}

[[gnu::always_inline]] inline
void Simulator::AddContactImpulse(const ClosedContact& c, const Eigen::Vector4d& percussion) {
  // W Λ on a side: sign (LᵀΛ, JᵀΛ); Λ is zero beyond the contact's dimension
  const Eigen::Vector3d linear = c.jacobian.linear.transpose() * percussion;
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    BodyStep& w = body_step_[static_cast<std::size_t>(side.body)];
    w.linear_contact += side.sign * linear;
    w.angular_contact += side.sign * (side.angular.transpose() * percussion);
  }
}

void Simulator::ApplyImpulses(const Island& island) {
  // (18) the contact part M⁻¹ Σ W_i Λ_i, per body
  const std::size_t index = static_cast<std::size_t>(&island - islands_.data());
  for (int k = island_body_start_[index]; k < island_body_start_[index + 1]; ++k) {
    BodyStep& w = body_step_[static_cast<std::size_t>(island_bodies_[static_cast<std::size_t>(k)])];
    w.linear_contact.setZero();
    w.angular_contact.setZero();
  }
  for (int k = 0; k < island.contact_count; ++k) {
    AddContactImpulse(closed_[static_cast<std::size_t>(island_contacts_[static_cast<std::size_t>(
                          island.first_contact + k)])],
                      lambda_[static_cast<std::size_t>(k)]);
  }
}

[[gnu::always_inline]] inline
void Simulator::RememberSolve(ClosedContact* contact, const Eigen::Vector4d& percussion,
                              bool friction_projected, bool alone, double rim_hint) {
  ClosedContact& c = *contact;
  c.report.percussion = percussion;
  ContactMemory& memory = *c.memory;
  memory.sliding = friction_projected && c.report.dimension > 1;
  memory.converged = island_stats_.converged;
  memory.tangent1 = c.report.frame.tangent1;
  // the next start is quadratic if that would have been the closer start of this solve, in a
  // smooth stretch of a contact alone in its island: closed in the last three steps, this
  // solve converged within two iterations (not an impact, a stick-slip switch or a slow
  // drilling mode, where the quadratic's larger weights on the solver's round-off make the
  // start worse); alone, as its percussion is then unique (several contacts can share a load
  // in many ways, and the shares wander: the two rolling feet of warm_start_test took twice
  // the iterations)
  memory.quadratic_served = false;
  if (alone && island_stats_.converged && island_stats_.iterations <= 2 &&
      memory.closed_step == step_count_ - 1 && memory.closed_before == step_count_ - 2 &&
      memory.closed_before2 == step_count_ - 3) {
    memory.quadratic_served = (QuadraticStart(memory) - percussion).cwiseAbs().maxCoeff() <
                              (LinearStart(memory) - percussion).cwiseAbs().maxCoeff();
  }
  memory.percussion_before2 = memory.percussion_before;
  memory.percussion_before = memory.percussion;
  memory.percussion = percussion;
  if (c.report.law.friction_set == FrictionSet::kExact) memory.rim_hint = rim_hint;
  memory.closed_before2 = memory.closed_before;
  memory.closed_before = memory.closed_step;
  memory.closed_step = step_count_;
}

bool Simulator::SolveLoneContact(const Island& island, StepStatistics* stats) {
  const std::size_t i =
      static_cast<std::size_t>(island_contacts_[static_cast<std::size_t>(island.first_contact)]);
  ClosedContact& c = closed_[i];
  const ContactMemory& memory = *c.memory;
  Eigen::Vector4d lambda = WarmStart(memory, options_.extrapolate_warm_start);
  const bool exact = c.report.law.friction_set == FrictionSet::kExact;
  double rim_hint = memory.closed_step == step_count_ - 1
                        ? memory.rim_hint
                        : std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix4d G = DelassusBlock(c, c);
  // a body far away can overflow G, a diverged state (huge ω) c: not solved
  if (!AllFinite(G)) return false;
  const Eigen::Vector4d free_velocity = FreeContactVelocity(c);
  if (!AllFinite(free_velocity)) return false;
  solver_.SolveOnePrevalidated(G, free_velocity, c.report.law, options_.solver, &lambda,
                               &island_stats_, exact ? &rim_hint : nullptr);
  // (18) on its one or two bodies
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    BodyStep& w = body_step_[static_cast<std::size_t>(side.body)];
    w.linear_contact.setZero();
    w.angular_contact.setZero();
  }
  AddContactImpulse(c, lambda);
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const std::size_t b = static_cast<std::size_t>(side.body);
    BodyStep& w = body_step_[b];
    w.angular_end = w.angular_free + InverseInertiaTimes(inertia_[b], w.angular_contact);
  }
  stats->solver.iterations += island_stats_.iterations;
  stats->solver.residual = std::max(stats->solver.residual, island_stats_.residual);
  stats->solver.max_change = std::max(stats->solver.max_change, island_stats_.max_change);
  stats->solver.converged = stats->solver.converged && island_stats_.converged;
  stats->gyroscopic_passes = std::max(stats->gyroscopic_passes, 1);
  stats->solver.friction_projected[i] = island_stats_.friction_projected[0];
  stats->solver.normal_projected[i] = island_stats_.normal_projected[0];
  RememberSolve(&c, lambda, island_stats_.friction_projected[0], /*alone=*/true, rim_hint);
  return true;
}

bool Simulator::SolveIsland(const Island& island, StepStatistics* stats) {
  // one contact (a top on the ground) on an explicit step: without the block problem
  if (island.contact_count == 1 && !implicit_step_) return SolveLoneContact(island, stats);
  const double dt = options_.time_step;
  const std::size_t index = static_cast<std::size_t>(&island - islands_.data());
  const int body_begin = island_body_start_[index];
  const int body_end = island_body_start_[index + 1];
  const int m = island.contact_count;
  auto contact = [this, &island](int k) -> ClosedContact& {
    return closed_[static_cast<std::size_t>(
        island_contacts_[static_cast<std::size_t>(island.first_contact + k)])];
  };
  problem_.Resize(m);
  if (lambda_.size() < static_cast<std::size_t>(m)) {
    lambda_.resize(static_cast<std::size_t>(m));
    rim_hints_.resize(static_cast<std::size_t>(m));
  }
  // extrapolated starts (simulator.h) in an island of one contact or of contacts that all slid
  const auto slid = [&](int k) {
    const ContactMemory& memory = *contact(k).memory;
    return memory.sliding && memory.closed_step == step_count_ - 1;
  };
  bool extrapolating = options_.extrapolate_warm_start;
  for (int k = 0; m > 1 && k < m && extrapolating; ++k) extrapolating = slid(k);
  // B_F's exact prox is warm-started too (its hint); other sets have none to carry
  bool any_exact = false;
  for (int k = 0; k < m; ++k) {
    const ClosedContact& c = contact(k);
    problem_.laws[static_cast<std::size_t>(k)] = c.report.law;
    any_exact = any_exact || c.report.law.friction_set == FrictionSet::kExact;
    lambda_[static_cast<std::size_t>(k)] = WarmStart(*c.memory, extrapolating);
    rim_hints_[static_cast<std::size_t>(k)] = c.memory->closed_step == step_count_ - 1
                                                  ? c.memory->rim_hint
                                                  : std::numeric_limits<double>::quiet_NaN();
  }

  // (16) the blocks G_ij, padded
  for (int i = 0; i < m; ++i) {
    const ClosedContact& a = contact(i);
    for (int j = i; j < m; ++j) {
      Eigen::Matrix4d& block = problem_.G[static_cast<std::size_t>(i * m + j)];
      block = DelassusBlock(a, contact(j));
      if (j != i) problem_.G[static_cast<std::size_t>(j * m + i)] = block.transpose();
      // a body far away can overflow G: not solved
      if (!AllFinite(block)) return false;
    }
  }

  const bool implicit = implicit_step_;
  const double pass_tolerance = std::max(options_.solver.tolerance_rel, kGyroscopicRoundOff);
  int total_iterations = 0;
  int passes = 0;
  for (int pass = 0; pass < kMaxGyroscopicPasses; ++pass) {
    // (16) c_i, with this pass's gyroscopic impulse
    bool finite = true;
    for (int k = 0; k < m; ++k) {
      Eigen::Vector4d& ci = problem_.c[static_cast<std::size_t>(k)];
      ci = FreeContactVelocity(contact(k));
      finite = finite && AllFinite(ci);
    }
    // a diverged state (huge ω) can overflow c: not solved
    if (!finite) return false;
    // (17); the problem is valid by construction (G_ii > 0: every contact moves a body), the
    // options were validated when set
    solver_.SolvePrevalidated(problem_, options_.solver, &lambda_, &island_stats_,
                              any_exact ? &rim_hints_ : nullptr);
    total_iterations += island_stats_.iterations;
    passes = pass + 1;
    ApplyImpulses(island);
    if (!implicit) {
      for (int k = body_begin; k < body_end; ++k) {
        const std::size_t b = static_cast<std::size_t>(island_bodies_[static_cast<std::size_t>(k)]);
        BodyStep& w = body_step_[b];
        w.angular_end = w.angular_free + InverseInertiaTimes(inertia_[b], w.angular_contact);
      }
      break;
    }
    // implicit midpoint on Euler's equations for the current Λ; its gyroscopic impulse enters c
    // of the next pass
    bool settled = true;
    for (int k = body_begin; k < body_end; ++k) {
      const std::size_t b = static_cast<std::size_t>(island_bodies_[static_cast<std::size_t>(k)]);
      BodyStep& w = body_step_[b];
      const BodyInertia& body = inertia_[b];
      const Eigen::Vector3d& omega_begin = state_[b].angular_velocity;
      const Eigen::Vector3d guess =
          pass == 0 ? Eigen::Vector3d(w.angular_free + InverseInertiaTimes(body, w.angular_contact))
                    : w.angular_end;
      // an external torque's impulse with the contacts' (then gyroscopic_impulse below holds it
      // too, and angular_free stays ω_B + Θ⁻¹ times the impulse of h)
      const Eigen::Vector3d omega_end = ImplicitMidpointEuler(
          body, omega_begin,
          w.external ? Eigen::Vector3d(w.angular_contact + w.angular_external) : w.angular_contact,
          dt, guess);
      if ((omega_end - guess).norm() > pass_tolerance * omega_end.norm()) settled = false;
      w.angular_end = omega_end;
      // the gyroscopic impulse -Δt ω_M × Θω_M that this ω_E balances
      w.gyroscopic_impulse = body.inertia * (omega_end - omega_begin) - w.angular_contact;
      w.angular_free = omega_begin + InverseInertiaTimes(body, w.gyroscopic_impulse);
    }
    if (settled) break;
  }

  // statistics over the islands
  stats->solver.iterations += total_iterations;
  stats->solver.residual = std::max(stats->solver.residual, island_stats_.residual);
  stats->solver.max_change = std::max(stats->solver.max_change, island_stats_.max_change);
  stats->solver.converged = stats->solver.converged && island_stats_.converged;
  stats->gyroscopic_passes = std::max(stats->gyroscopic_passes, passes);
  // the percussions: reported, and the warm start of the next step
  for (int k = 0; k < island.contact_count; ++k) {
    ClosedContact& c = contact(k);
    const std::size_t i = static_cast<std::size_t>(
        island_contacts_[static_cast<std::size_t>(island.first_contact + k)]);
    stats->solver.friction_projected[i] =
        island_stats_.friction_projected[static_cast<std::size_t>(k)];
    stats->solver.normal_projected[i] = island_stats_.normal_projected[static_cast<std::size_t>(k)];
    RememberSolve(&c, lambda_[static_cast<std::size_t>(k)],
                  island_stats_.friction_projected[static_cast<std::size_t>(k)], m == 1,
                  rim_hints_[static_cast<std::size_t>(k)]);
  }
  return true;
}

}  // namespace nonsmooth_sim
