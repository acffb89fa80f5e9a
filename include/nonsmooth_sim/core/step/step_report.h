// What a step reports: its closed contacts (ContactState) and its statistics (StepStatistics).
#ifndef NONSMOOTH_SIM_CORE_STEP_STEP_REPORT_H_
#define NONSMOOTH_SIM_CORE_STEP_STEP_REPORT_H_

#include <Eigen/Core>
#include <string>

#include "nonsmooth_sim/core/contact/contact_jacobian.h"
#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {

/// One contact of the index set (12) of the last step, at the midpoint q_M where it was found.
/// A and B are the two colliders, the normal points from A to B; a static collider is always A.
struct ContactState {
  int collider_a = 0;  ///< index into Scene::colliders
  int collider_b = 0;
  int body_a = kWorld;  ///< body of A (kWorld: static)
  int body_b = 0;       ///< body of B
  int feature = 0;      ///< ContactGeometry::feature of the pair function
  double gap = 0.0;     ///< g(q_M) ≤ 0 [m]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< contact point on B, world [m]
  ContactFrame frame;   ///< n (A → B), t1, t2, world
  ContactLaw law;       ///< the pair's law (CombineLaws), R̄ of a face patch where it is one
  int dimension = 1;    ///< ContactDimensionWithRolling(law): 1, 3, 4 or 6
  /// Λ = (Λ_N, Λ_T1, Λ_T2, Λ_τ) on B [N s, N s, N s, N m s]; components the contact does not
  /// model are 0.
  Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
  /// Λ_R = (Λ_R1, Λ_R2), the rolling percussion on B about t1, t2 [N m s]; 0 unless the contact
  /// has rolling components (dimension 6)
  Eigen::Vector2d rolling_percussion = Eigen::Vector2d::Zero();
  /// γ_E = W(q_M)ᵀu_E [m/s, m/s, m/s, rad/s]: velocity of B relative to A, the one the law
  /// constrained.
  Eigen::Vector4d relative_velocity = Eigen::Vector4d::Zero();
};

/// "<first>/<second>": the two colliders' names in Scene::colliders order (e.g.
/// "big_sphere/ground"). Stable while the scene does not change.
std::string ContactName(const Scene& scene, const ContactState& contact);
struct StepStatistics {
  /// Over the islands' contact solves: iterations summed (and over the passes of
  /// kImplicitMidpoint), residual and max_change the largest, converged if every island did;
  /// friction_projected / normal_projected per contact of contacts(). With no closed contact
  /// iterations = 0 and converged = true.
  SolverStatistics solver;
  int closed_contacts = 0;
  int islands = 0;  ///< contact problems (17) solved: bodies linked by closed contacts
  /// Deepest penetration of a closed contact at the midpoint, max(0, -g(q_M)) [m].
  double max_penetration = 0.0;
  int gyroscopic_passes = 0;  ///< contact solves of this step (1 with kExplicit; 0 without contact)
  /// Largest Δt·|ω| over the bodies in this step: the explicit gyroscopic scheme's energy error
  /// per step grows like (Δt·|ω|)².
  double max_dt_omega = 0.0;
  /// gyroscopic == kExplicit and max_dt_omega > kExplicitGyroscopicMaxDtOmega: energy can grow by
  /// O((Δt·|ω|)²) per step and the run can diverge.
  bool explicit_gyroscopic_unsafe = false;
  /// The deepest g(q_M) < 0 of a contact that closed in this step and not in the last one (an
  /// impact found part of a step late: the depth is the position error that lateness makes;
  /// AdaptiveStepper shrinks the step until it is small) [m], 0 without such a contact.
  double new_contact_depth = 0.0;
  /// Largest translation |Δr| of a body by SimulatorOptions::gap_correction in this step [m]
  /// (0: none).
  double gap_correction = 0.0;
  /// Potential energy the lifts added in this step, Σ -m g·Δr over the moved bodies [J].
  double gap_correction_energy = 0.0;
  /// Energy() of the state after this step, gap correction included [J]: the step sums it anyway
  /// (the state must not overflow it), so a caller need not sum it again. NaN if the step was not
  /// taken (state_finite false).
  double energy = 0.0;
  /// false: this step met a non-finite value (state, free velocities, contact problem, end state or
  /// the squared norms of the end velocities), i.e. the scheme diverged. The step was not taken:
  /// state, time and contact report stay at the last finite step, and every later Step() returns at
  /// once with state_finite = false (nothing advances) until SetState() replaces the state
  /// (Simulator::diverged()). The mechanical energy of the end state (Energy(), as MechanicalEnergy
  /// sums it) overflowing counts as non-finite too.
  bool state_finite = true;
  /// true: SimulatorOptions::gap_correction produced a non-finite value in this step (a position or
  /// orientation, the energy, or gap_correction / gap_correction_energy overflowing; only for
  /// bodies set through the core absurdly far into the ground, e.g. 1e300 m) and was undone: the
  /// state is the step's end state without the correction, as with gap_correction = false, and
  /// gap_correction = gap_correction_energy = 0. The step is taken (state_finite stays true).
  bool gap_correction_undone = false;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_STEP_REPORT_H_
