// The contact problem (17) of one island and the impulses (18) it gives, see island_problem.h.
#include "nonsmooth_sim/core/step/island_problem.h"

#include <algorithm>
#include <limits>

#include "nonsmooth_sim/core/all_finite.h"

namespace nonsmooth_sim {
namespace {

// The implicit-midpoint passes stop once ω_E changes by less than this relative amount even when
// the solver tolerance is tighter: below it the change is round-off.
constexpr double kGyroscopicRoundOff = 4.0 * std::numeric_limits<double>::epsilon();

// Whether the law's prox carries its own warm start from step to step (its row's warm-start kind,
// friction_law.h): B_F's last foot point.
bool CarriesRimHint(const ContactLaw& law) {
  return LawIs<&FrictionLaw::warm_start, WarmStartKind::kPercussionAndRimHint>(law.friction_set);
}

}  // namespace

bool IslandProblem::HasRollingContact(const Islands& islands, std::size_t index,
                                      const StepData& data) {
  const Island& island = islands.islands()[index];
  for (int k = 0; k < island.contact_count; ++k) {
    if (data.closed[static_cast<std::size_t>(islands.contact(island, k))].report.dimension == 6) {
      return true;
    }
  }
  return false;
}

template <bool kRolling>
void IslandProblem::ApplyImpulses(const Islands& islands, std::size_t index,
                                  StepData* data) const {
  // (18) the contact part M⁻¹ Σ W_i Λ_i, per body
  const Island& island = islands.islands()[index];
  for (int k = islands.body_begin(index); k < islands.body_end(index); ++k) {
    BodyStep& w = data->body[static_cast<std::size_t>(islands.body(k))];
    w.linear_contact.setZero();
    w.angular_contact.setZero();
  }
  for (int k = 0; k < island.contact_count; ++k) {
    const ClosedContact& c = data->closed[static_cast<std::size_t>(islands.contact(island, k))];
    if constexpr (kRolling) {
      const Vector6d& lambda = rolling_lambda_[static_cast<std::size_t>(k)];
      AddContactImpulse(c, lambda.head<4>(), &data->body);
      if (c.report.dimension == 6) AddRollingImpulse(c, lambda.tail<2>(), &data->body);
    } else {
      AddContactImpulse(c, lambda_[static_cast<std::size_t>(k)], &data->body);
    }
  }
}

[[gnu::always_inline]] inline
void IslandProblem::RememberSolve(ClosedContact* contact, const Eigen::Vector4d& percussion,
                                  bool friction_projected, bool alone, double rim_hint,
                                  long step) const {
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
      memory.closed_step == step - 1 && memory.closed_before == step - 2 &&
      memory.closed_before2 == step - 3) {
    memory.quadratic_served = (QuadraticStart(memory) - percussion).cwiseAbs().maxCoeff() <
                              (LinearStart(memory) - percussion).cwiseAbs().maxCoeff();
  }
  memory.percussion_before2 = memory.percussion_before;
  memory.percussion_before = memory.percussion;
  memory.percussion = percussion;
  if (CarriesRimHint(c.report.law)) memory.rim_hint = rim_hint;
  memory.closed_before2 = memory.closed_before;
  memory.closed_before = memory.closed_step;
  memory.closed_step = step;
}

bool IslandProblem::SolveLoneContact(const Model& model, const SimulatorOptions& options,
                                     std::size_t i, StepData* data, StepStatistics* stats) {
  ClosedContact& c = data->closed[i];
  const ContactMemory& memory = *c.memory;
  const long step = data->step;
  Eigen::Vector4d lambda = WarmStart(memory, step, options.extrapolate_warm_start);
  const bool rim_hinted = CarriesRimHint(c.report.law);
  double rim_hint =
      memory.closed_step == step - 1 ? memory.rim_hint : std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix4d G = DelassusBlock(model.inertia, c, c);
  // a body far away can overflow G, a diverged state (huge ω) c: not solved
  if (!AllFinite(G)) return false;
  const Eigen::Vector4d free_velocity = FreeContactVelocity(data->body, c);
  if (!AllFinite(free_velocity)) return false;
  solver_.SolveOnePrevalidated(G, free_velocity, c.report.law, options.solver, &lambda,
                               &island_stats_, rim_hinted ? &rim_hint : nullptr);
  // (18) on its one or two bodies
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    BodyStep& w = data->body[static_cast<std::size_t>(side.body)];
    w.linear_contact.setZero();
    w.angular_contact.setZero();
  }
  AddContactImpulse(c, lambda, &data->body);
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const std::size_t b = static_cast<std::size_t>(side.body);
    BodyStep& w = data->body[b];
    w.angular_end = w.angular_free + InverseInertiaTimes(model.inertia[b], w.angular_contact);
  }
  stats->solver.iterations += island_stats_.iterations;
  stats->solver.residual = std::max(stats->solver.residual, island_stats_.residual);
  stats->solver.max_change = std::max(stats->solver.max_change, island_stats_.max_change);
  stats->solver.converged = stats->solver.converged && island_stats_.converged;
  stats->gyroscopic_passes = std::max(stats->gyroscopic_passes, 1);
  stats->solver.friction_projected[i] = island_stats_.friction_projected[0];
  stats->solver.normal_projected[i] = island_stats_.normal_projected[0];
  RememberSolve(&c, lambda, island_stats_.friction_projected[0], /*alone=*/true, rim_hint, step);
  return true;
}

template <bool kRolling>
bool IslandProblem::SolveBlocks(const Model& model, const SimulatorOptions& options,
                                const std::vector<BodyState>& state, const Islands& islands,
                                std::size_t index, StepData* data, StepStatistics* stats) {
  const Island& island = islands.islands()[index];
  const double dt = options.time_step;
  const long step = data->step;
  const int body_begin = islands.body_begin(index);
  const int body_end = islands.body_end(index);
  const int m = island.contact_count;
  auto contact = [data, &islands, &island](int k) -> ClosedContact& {
    return data->closed[static_cast<std::size_t>(islands.contact(island, k))];
  };
  // the problem and percussions in 4-blocks, or in 6-blocks for an island with rolling
  auto& problem = [this]() -> auto& {
    if constexpr (kRolling) {
      return rolling_problem_;
    } else {
      return problem_;
    }
  }();
  auto& lambda = [this]() -> auto& {
    if constexpr (kRolling) {
      return rolling_lambda_;
    } else {
      return lambda_;
    }
  }();
  problem.Resize(m);
  if (lambda.size() < static_cast<std::size_t>(m)) {
    lambda.resize(static_cast<std::size_t>(m));
  }
  if (rim_hints_.size() < static_cast<std::size_t>(m)) {
    rim_hints_.resize(static_cast<std::size_t>(m));
  }
  // extrapolated starts (simulator.h) in an island of one contact or of contacts that all slid
  const auto slid = [&](int k) {
    const ContactMemory& memory = *contact(k).memory;
    return memory.sliding && memory.closed_step == step - 1;
  };
  bool extrapolating = options.extrapolate_warm_start;
  for (int k = 0; m > 1 && k < m && extrapolating; ++k) extrapolating = slid(k);
  // B_F's exact prox is warm-started too (its hint); other sets have none to carry
  bool any_rim_hint = false;
  const bool second_order = data->second_order;
  for (int k = 0; k < m; ++k) {
    ClosedContact& c = contact(k);
    // kMoreau2: friction against the midpoint velocity while a persistent contact slides
    c.friction_midpoint = second_order && c.report.dimension > 1 &&
                          c.memory->closed_step == step - 1 && c.memory->sliding;
    problem.laws[static_cast<std::size_t>(k)] = c.report.law;
    any_rim_hint = any_rim_hint || CarriesRimHint(c.report.law);
    if constexpr (kRolling) {
      Vector6d& start = lambda[static_cast<std::size_t>(k)];
      start.head<4>() = WarmStart(*c.memory, step, extrapolating);
      start.tail<2>() = c.report.dimension == 6 && c.memory->closed_step == step - 1
                            ? c.memory->rolling_percussion
                            : Eigen::Vector2d::Zero();
    } else {
      lambda[static_cast<std::size_t>(k)] = WarmStart(*c.memory, step, extrapolating);
    }
    rim_hints_[static_cast<std::size_t>(k)] = c.memory->closed_step == step - 1
                                                  ? c.memory->rim_hint
                                                  : std::numeric_limits<double>::quiet_NaN();
  }

  // (16) the blocks G_ij, padded
  for (int i = 0; i < m; ++i) {
    const ClosedContact& a = contact(i);
    for (int j = i; j < m; ++j) {
      auto& block = problem.G[static_cast<std::size_t>(i * m + j)];
      if constexpr (kRolling) {
        block = RollingDelassusBlock(model.inertia, a, contact(j));
      } else {
        block = DelassusBlock(model.inertia, a, contact(j));
      }
      if (j != i) problem.G[static_cast<std::size_t>(j * m + i)] = block.transpose();
      // a body far away can overflow G: not solved
      if (!AllFinite(block)) return false;
    }
  }

  const bool implicit = data->implicit;
  const double pass_tolerance = std::max(options.solver.tolerance_rel, kGyroscopicRoundOff);
  int total_iterations = 0;
  int passes = 0;
  const auto free_velocity4 = [&](int k) {
    return second_order ? SecondOrderContactVelocity(data->body, contact(k), dt,
                                                     data->previous_time_step, step)
                        : FreeContactVelocity(data->body, contact(k));
  };
  const auto free_velocity = [&](int k) {
    if constexpr (kRolling) {
      Vector6d velocity;
      velocity.head<4>() = free_velocity4(k);
      velocity.tail<2>() = contact(k).report.dimension == 6
                               ? RollingFreeVelocity(data->body, contact(k),
                                                     second_order ? &state : nullptr)
                               : Eigen::Vector2d::Zero();
      return velocity;
    } else {
      return free_velocity4(k);
    }
  };
  // (17); the problem is valid by construction (G_ii > 0: every contact moves a body), the
  // options were validated when set
  const auto solve = [&]() {
    if constexpr (kRolling) {
      rolling_solver_.SolvePrevalidated(rolling_problem_, options.solver, &rolling_lambda_,
                                        &island_stats_, any_rim_hint ? &rim_hints_ : nullptr);
    } else {
      solver_.SolvePrevalidated(problem_, options.solver, &lambda_, &island_stats_,
                                any_rim_hint ? &rim_hints_ : nullptr);
    }
  };
  for (int pass = 0; pass < kMaxGyroscopicPasses; ++pass) {
    // (16) c_i, with this pass's gyroscopic impulse
    bool finite = true;
    for (int k = 0; k < m; ++k) {
      auto& ci = problem.c[static_cast<std::size_t>(k)];
      ci = free_velocity(k);
      finite = finite && AllFinite(ci);
    }
    // a diverged state (huge ω) can overflow c: not solved
    if (!finite) return false;
    solve();
    total_iterations += island_stats_.iterations;
    if (second_order) {
      // kMoreau2: a contact that slid and now sticks has its law on the end velocity instead
      // (on the midpoint velocity a stick would reverse the slip), solved again
      bool again = false;
      for (int k = 0; k < m; ++k) {
        ClosedContact& c = contact(k);
        if (c.friction_midpoint && !island_stats_.friction_projected[static_cast<std::size_t>(k)]) {
          c.friction_midpoint = false;
          again = true;
        }
      }
      if (again) {
        for (int k = 0; k < m; ++k) problem.c[static_cast<std::size_t>(k)] = free_velocity(k);
        solve();
        total_iterations += island_stats_.iterations;
      }
    }
    passes = pass + 1;
    ApplyImpulses<kRolling>(islands, index, data);
    if (!implicit) {
      for (int k = body_begin; k < body_end; ++k) {
        const std::size_t b = static_cast<std::size_t>(islands.body(k));
        BodyStep& w = data->body[b];
        w.angular_end = w.angular_free + InverseInertiaTimes(model.inertia[b], w.angular_contact);
      }
      break;
    }
    // implicit midpoint on Euler's equations for the current Λ; its gyroscopic impulse enters c
    // of the next pass
    bool settled = true;
    for (int k = body_begin; k < body_end; ++k) {
      const std::size_t b = static_cast<std::size_t>(islands.body(k));
      BodyStep& w = data->body[b];
      const BodyInertia& body = model.inertia[b];
      const Eigen::Vector3d& omega_begin = state[b].angular_velocity;
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
    const std::size_t i = static_cast<std::size_t>(islands.contact(island, k));
    stats->solver.friction_projected[i] =
        island_stats_.friction_projected[static_cast<std::size_t>(k)];
    stats->solver.normal_projected[i] = island_stats_.normal_projected[static_cast<std::size_t>(k)];
    if constexpr (kRolling) {
      const Vector6d& percussion = lambda[static_cast<std::size_t>(k)];
      RememberSolve(&c, percussion.head<4>(),
                    island_stats_.friction_projected[static_cast<std::size_t>(k)], m == 1,
                    rim_hints_[static_cast<std::size_t>(k)], step);
      if (c.report.dimension == 6) {
        c.report.rolling_percussion = percussion.tail<2>();
        c.memory->rolling_percussion = percussion.tail<2>();
      }
    } else {
      RememberSolve(&c, lambda[static_cast<std::size_t>(k)],
                    island_stats_.friction_projected[static_cast<std::size_t>(k)], m == 1,
                    rim_hints_[static_cast<std::size_t>(k)], step);
    }
  }
  return true;
}

template bool IslandProblem::SolveBlocks<false>(const Model&, const SimulatorOptions&,
                                                const std::vector<BodyState>&, const Islands&,
                                                std::size_t, StepData*, StepStatistics*);
template bool IslandProblem::SolveBlocks<true>(const Model&, const SimulatorOptions&,
                                               const std::vector<BodyState>&, const Islands&,
                                               std::size_t, StepData*, StepStatistics*);

void SolveFreeBodiesImplicit(const Model& model, const SimulatorOptions& options,
                             const std::vector<BodyState>& state, const Islands& islands,
                             StepData* data) {
  for (std::size_t b = 0; b < state.size(); ++b) {
    if (islands.island_of(b) >= 0) continue;
    BodyStep& w = data->body[b];
    // torque-free unless an external torque acts (its impulse in K, ComputeMidpoints)
    const Eigen::Vector3d impulse =
        w.external ? w.angular_external : Eigen::Vector3d(Eigen::Vector3d::Zero());
    w.angular_end = ImplicitMidpointEuler(model.inertia[b], state[b].angular_velocity, impulse,
                                          options.time_step, w.angular_free);
  }
}

}  // namespace nonsmooth_sim
