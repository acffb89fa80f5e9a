// The contact problem (17) of one island and the impulses (18) it gives, see simulator.h.
#include <algorithm>
#include <limits>

#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

// The implicit-midpoint passes stop once ω_E changes by less than this relative amount even when
// the solver tolerance is tighter: below it the change is round-off.
constexpr double kGyroscopicRoundOff = 4.0 * std::numeric_limits<double>::epsilon();

}  // namespace

ContactProblem& Simulator::ProblemOfSize(int size) {
  const std::size_t n = static_cast<std::size_t>(size);
  if (problems_.size() <= n) {
    problems_.resize(n + 1);
    lambdas_.resize(n + 1);
  }
  ContactProblem& problem = problems_[n];
  if (problem.G.rows() != size) {
    problem.G.setZero(size, size);
    problem.c.setZero(size);
    problem.contacts.reserve(n);
    lambdas_[n].setZero(size);
  }
  return problem;
}

void Simulator::ApplyImpulses(const Island& island, const Eigen::VectorXd& lambda) {
  // (18) the contact part M⁻¹ Σ W_i Λ_i, per body
  for (int k = island_body_start_[static_cast<std::size_t>(&island - islands_.data())];
       k < island_body_start_[static_cast<std::size_t>(&island - islands_.data()) + 1]; ++k) {
    BodyStep& w = body_step_[static_cast<std::size_t>(island_bodies_[static_cast<std::size_t>(k)])];
    w.linear_contact.setZero();
    w.angular_contact.setZero();
  }
  for (int k = 0; k < island.contact_count; ++k) {
    const ClosedContact& c = closed_[static_cast<std::size_t>(
        island_contacts_[static_cast<std::size_t>(island.first_contact + k)])];
    Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
    // (element loops: Eigen's dynamic-size segments cost more than the copy at 1-4 entries)
    for (int d = 0; d < c.report.dimension; ++d) percussion[d] = lambda[c.offset + d];
    // W Λ on a side: sign (LᵀΛ, JᵀΛ)
    const Eigen::Vector3d linear = c.jacobian.linear.transpose() * percussion;
    for (const ContactSide& side : c.jacobian.side) {
      if (side.body < 0) continue;
      BodyStep& w = body_step_[static_cast<std::size_t>(side.body)];
      w.linear_contact += side.sign * linear;
      w.angular_contact += side.sign * (side.angular.transpose() * percussion);
    }
  }
}

bool Simulator::SolveIsland(const Island& island, StepStatistics* stats) {
  const double dt = options_.time_step;
  const std::size_t index = static_cast<std::size_t>(&island - islands_.data());
  const int body_begin = island_body_start_[index];
  const int body_end = island_body_start_[index + 1];
  auto contact = [this, &island](int k) -> ClosedContact& {
    return closed_[static_cast<std::size_t>(
        island_contacts_[static_cast<std::size_t>(island.first_contact + k)])];
  };
  ContactProblem& problem = ProblemOfSize(island.size);
  Eigen::VectorXd& lambda = lambdas_[static_cast<std::size_t>(island.size)];
  problem.contacts.clear();
  for (int k = 0; k < island.contact_count; ++k) {
    const ClosedContact& c = contact(k);
    problem.contacts.push_back(ContactBlock{c.offset, c.report.law});
    // warm start from the previous step's percussions (zero if the contact was open then)
    const bool warm = c.memory->closed_step == step_count_ - 1;
    for (int d = 0; d < c.report.dimension; ++d) {
      lambda[c.offset + d] = warm ? c.memory->percussion[d] : 0.0;
    }
  }

  // (16) G_ij = W_iᵀ M⁻¹ W_j over the sides the two contacts share a body on
  for (int i = 0; i < island.contact_count; ++i) {
    const ClosedContact& a = contact(i);
    for (int j = i; j < island.contact_count; ++j) {
      const ClosedContact& b = contact(j);
      Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
      for (const ContactSide& s : a.jacobian.side) {
        if (s.body < 0) continue;
        for (const ContactSide& t : b.jacobian.side) {
          if (t.body != s.body) continue;
          block += SideDelassusBlock(inertia_[static_cast<std::size_t>(s.body)], a.jacobian, s,
                                     b.jacobian, t);
        }
      }
      const int da = a.report.dimension;
      const int db = b.report.dimension;
      if (da == 4 && db == 4) {
        problem.G.block<4, 4>(a.offset, b.offset) = block;
        if (j != i) problem.G.block<4, 4>(b.offset, a.offset) = block.transpose();
        continue;
      }
      problem.G.block(a.offset, b.offset, da, db) = block.topLeftCorner(da, db);
      if (j != i)
        problem.G.block(b.offset, a.offset, db, da) = block.topLeftCorner(da, db).transpose();
    }
  }

  const bool implicit = implicit_step_;
  const double pass_tolerance = std::max(options_.solver.tolerance_rel, kGyroscopicRoundOff);
  int total_iterations = 0;
  int passes = 0;
  for (int pass = 0; pass < kMaxGyroscopicPasses; ++pass) {
    // (16) c_i = W_iᵀ M⁻¹ h Δt + (1 + ε_i) γ_i^B = W_iᵀ(u_B + M⁻¹hΔt) + ε_i γ_i^B
    for (int k = 0; k < island.contact_count; ++k) {
      const ClosedContact& c = contact(k);
      Eigen::Vector4d gamma_free = Eigen::Vector4d::Zero();
      for (const ContactSide& side : c.jacobian.side) {
        if (side.body < 0) continue;
        const BodyStep& w = body_step_[static_cast<std::size_t>(side.body)];
        gamma_free += SideVelocity(c.jacobian, side, w.linear_free, w.angular_free);
      }
      const Eigen::Vector4d ci = gamma_free + c.report.law.restitution * c.gamma_begin;
      for (int d = 0; d < c.report.dimension; ++d) problem.c[c.offset + d] = ci[d];
    }
    // a diverged state (huge ω) can overflow c (and G, with a body far away): not solved
    if (!problem.c.allFinite() || !problem.G.allFinite()) return false;
    // (17); the problem is valid by construction (G_ii > 0: every contact moves a body), the
    // options were validated when set
    solver_.SolvePrevalidated(problem, options_.solver, &lambda, &island_stats_);
    total_iterations += island_stats_.iterations;
    passes = pass + 1;
    ApplyImpulses(island, lambda);
    if (!implicit) {
      for (int k = body_begin; k < body_end; ++k) {
        const std::size_t b = static_cast<std::size_t>(island_bodies_[static_cast<std::size_t>(k)]);
        BodyStep& w = body_step_[b];
        w.angular_end = w.angular_free + inertia_[b].inverse_inertia * w.angular_contact;
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
          pass == 0 ? Eigen::Vector3d(w.angular_free + body.inverse_inertia * w.angular_contact)
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
      w.angular_free = omega_begin + body.inverse_inertia * w.gyroscopic_impulse;
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
    c.report.percussion.setZero();
    for (int d = 0; d < c.report.dimension; ++d) c.report.percussion[d] = lambda[c.offset + d];
    c.memory->tangent1 = c.report.frame.tangent1;
    c.memory->percussion = c.report.percussion;
    c.memory->closed_step = step_count_;
  }
  return true;
}

}  // namespace nonsmooth_sim
