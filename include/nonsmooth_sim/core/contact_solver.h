// Fixed-point solver for the contact inclusion (17) of one time step.
//
// Möller, Leine, Glocker (ESMC 2009), sections 3-5. For every closed contact i the percussion
// Λ_i = (Λ_N, Λ_T1, Λ_T2, Λ_τ) (components present only where the contact models them) satisfies
//
//   ξ_i ∈ N_{D_i}(-Λ_i),   ξ_i = Σ_j G_ij Λ_j + c_i                                   (17)
//
// with the Delassus blocks G_ij = W_iᵀ M⁻¹ W_j and c_i of (16). D_i is the product of the
// unilateral normal set and the friction set of the contact's law, scaled by the current iterate
// of Λ_N (the usual fixed point for Coulomb friction): within one contact update Λ_N is projected
// first and the friction set gets the radius μ·Λ_N^{ν+1}.
//
// Sign convention: the sets are written for Λ (C = -D, see force_sets.h), so -ξ_i ∈ N_{C_i}(Λ_i)
// and (37) reads Λ^{ν+1} = prox_C(Λ^ν - r (GΛ^ν + c)).
//
// Every contact is iterated in the coordinates Λ̂_i = A_i⁻¹Λ_i with Ĝ_ij = A_iᵀ G_ij A_j and
// ĉ_i = A_iᵀ c_i (41) (transformation.h, ContactMapDiagonal), on the set Ĉ_i = A_i⁻¹C_i, and the
// result is mapped back, Λ_i = A_iΛ̂_i (47). A_i = diag(1, 1, 1, a_τ) on (N, T1, T2, τ):
//
//   law        iterated on                                 a_τ  equations
//   coulomb    the disk ||Λ_T|| ≤ μΛ_N                     -    (37)
//   sphere     S_F = A⁻¹E_F (57)-(59)                      R̄    (40)-(47), A of (56)
//   ellipsoid  E_F (55) itself                             1    (37): by definition the paper's
//                                                                untransformed reference
//   exact      map_drilling_sets: A⁻¹B_F = B_F with R̄ = 1  R̄    (40)-(47), A of (56)
//              otherwise:         B_F (51)-(53) itself     1    (37), the paper's B_F timing
//   cylinder   map_drilling_sets: A⁻¹C_F = C_F with R̄ = 1  R̄    (40)-(47), A of (56)
//              otherwise:         C_F (54) itself          1    (37)
//
// A contact without a drilling component (μ = 0, or R̄ = 0, or coulomb) has A_i = I and every law
// is the coulomb disk there. B_F and C_F scale linearly along the drilling axis (b_τ ∝ R̄ in (52),
// the height R̄μΛ_N in (54)), so A⁻¹ with A of (56) maps them onto the same sets with R̄ = 1, whose
// Euclidean prox is the exact one (ProxCoulombContensou / ProxCylinder with rbar = 1). By (30)
// (any convex set, any non-singular A) the mapped iteration has the same solution Λ.
// Why map: in the projecting (sliding) case every friction component steps r̂ = α/max_k Ĝ_iikk,
// and the error along the boundary of the set shrinks roughly by ρ/(ρ + r̂|ξ̂_F|) per iteration
// (ρ = μΛ_N). On the original sets r̂ = α/G_ττ, and for the Tippe-Top G_ττ ≈ 3000 G_TT: the
// sliding iterates crawl (hundreds to thousands of iterations per step). With A of (56)
// Ĝ_ττ = R̄²G_ττ ≪ Ĝ_TT, so r̂ = α/max(Ĝ_NN, Ĝ_TT) is ~3000 times larger.
//
// Iterations (r̂_i, Ĝ, ĉ as above; for A_i = I the hats drop and (43) is (37)):
//  - kJacobi, (37)/(43): Λ̂_i^{ν+1} = prox_{Ĉ_i}(Λ̂_i^ν - r̂_i ξ̂_i^ν),  ξ̂_i^ν = Σ_j Ĝ_ij Λ̂_j^ν + ĉ_i,
//    one r̂_i = α / max_k Ĝ_iikk over all components k of contact i, normal included.
//  - kModifiedJacobi, (46). The contact is split into its two factor sets, each with its own
//    "projecting" flag:
//      normal block {Λ_N ≥ 0} (a half-line, 1-D): (46) on a 1-D block has r̂ = α/Ĝ_NN and Q = 1
//        in both cases, so  Λ_N^{ν+1} = max(0, Λ_N^ν - (α/Ĝ_NN) ξ̂_N);  projecting ⇔ the
//        argument is < 0. Λ_N never leaves its set.
//      friction block F (T1, T2[, τ]) with radius μΛ_N^{ν+1}: r̂_F = α / max_{k∈F} Ĝ_iikk,
//        z = Λ̂_F^ν - r̂_F ξ̂_F;  non-projecting (44) ⇔ z ∈ Ĉ_F (prox region kInterior):
//          y = Λ̂_F^ν - Q r̂_F ξ̂_F,  Q = diag(α / (r̂_F Ĝ_iikk)),  i.e. each component k steps
//          α/Ĝ_iikk (the Jacobi step of (45) without the max);  Λ̂_F^{ν+1} = y if y ∈ Ĉ_F,
//          otherwise Q = I:  Λ̂_F^{ν+1} = z  (the step of (43));
//        projecting (Q = I):  Λ̂_F^{ν+1} = prox_{Ĉ_F}(z).
//    Departure from the paper: (46) takes y whenever z ∈ Ĉ_F. Because the steps α/Ĝ_kk can be
//    far larger than r̂_F (Ĝ_ττ = R̄²G_ττ is tiny for the mapped laws), y can land far outside the
//    set, the next iteration projects back, and the iteration 2-cycles on a sliding contact (seen
//    on a single sphere-law contact of test ConstructedProblems). Accepting y only inside the set
//    keeps every friction iterate in its set and leaves the fixed points unchanged (Q is
//    regular in either case).
//    The fixed point is that of (43) because a block-diagonal R̂_i = diag(1/r̂_N, I/r̂_F) in
//    (39) has the same solutions as R̂_i = I/r̂_i (the sets are a product for a fixed Λ_N).
//  - kGaussSeidel: the equations of kModifiedJacobi, contact by contact, each contact using the
//    already updated percussions of the contacts before it (within a contact all components use
//    the same ξ̂_i).
//
// Convergence (the non-projecting, linear case; D̂ = diag(Ĝ), λ_max of the scaled matrices):
// kModifiedJacobi needs α < 2/λ_max(D̂^{-1/2} Ĝ D̂^{-1/2}) over the whole problem (sufficient for
// kJacobi too, whose steps are smaller); kGaussSeidel only α < 2/λ_max(D̂_i^{-1/2} Ĝ_ii D̂_i^{-1/2})
// for every contact (its splitting has M + Mᵀ - Ĝ = 2D̂/α - blockdiag(Ĝ_ii)). The diagonal map A
// does not change these numbers. Tippe-Top: one contact ≈ 1.2, so α = 1 is fine for every scheme;
// both spheres touching ≈ 2.65, so the Jacobi schemes need α < 0.75 there unless the contacts
// slide (bench/fixpoint_bench.cpp's rolling two-contact problem does not converge with α = 1);
// Gauss-Seidel does not.
//
// Stopping rule (per iteration ν, over all components k of all contacts i, in the original
// coordinates Λ = AΛ̂):
//   converged  ⇔  d_k ≤ tolerance_abs + tolerance_rel · |Λ_k^{ν+1}|  for all k,
//   d_k = max(|ΔΛ_k|, min(s_k|ΔΛ_k|, 2e_k)),  ΔΛ_k = Λ_k^{ν+1} - Λ_k^ν,
// e_k the half-width of contact i's friction set along k at the radius ρ = μΛ_N^{ν+1} (ρ for T1,
// T2; R̄ρ for τ; +inf for N), and s_k ≥ 1 the ratio of the step α/Ĝ_iikk natural to component k
// to the step r̂_k it took, σ_k = (α/Ĝ_iikk) / r̂_k:
//     kJacobi (43), every k:                       r̂_k = r̂_i      σ_k = max_l Ĝ_iill / Ĝ_iikk
//     kModifiedJacobi (46), kGaussSeidel:
//       normal block:                              α/Ĝ_iiNN         σ_N = 1
//       friction block, y accepted:                α/Ĝ_iikk         σ_k = 1
//       friction block, z (projecting, or y
//         outside the set):                        r̂_F             σ_k = max_{l∈F} Ĝ_iill / Ĝ_iikk
//   s_k = σ_k, except on a friction block whose prox acted in iteration ν (friction_projected):
//   s_k = min(σ_k, max(1, q/(1 - q))) for k ∈ F if q < 1, with the block's contraction estimate
//   q = max_{l∈F}|ΔΛ̂_l^ν| / max_{l∈F}|ΔΛ̂_l^{ν-1}| (ΔΛ̂^ν = Λ̂^{ν+1} - Λ̂^ν; ΔΛ̂^0 = 0: no cap in
//   the first iteration).
// (l over the components of contact i; s_k = 1 where a contact has no component k.) d_k estimates
// the distance to the solution rather than the step actually taken, and is never below |ΔΛ_k|
// (the plain increment test is necessary). Where the prox does not act, σ_k|ΔΛ̂_k| =
// (α/Ĝ_iikk)|ξ̂_k|, for a contact with a diagonal Ĝ_ii and no coupling α times the distance
// |Λ̂_k^ν - Λ̂_k*| of the old iterate from the solution (the new one's is |1 - α| times that).
// Without it the test is fooled by (43) on a badly scaled contact: r̂_i = α/max_l Ĝ_iill makes the
// steps of the components with a small Ĝ_iikk tiny, and |ΔΛ_k| passed the tolerance while Λ_N was
// still far from its solution (stability_solver_test.cpp, BadScaling). Where the prox acts, the set's
// curvature (≈ |ξ̂_F|/ρ along a curved boundary) adds to Ĝ_iikk and the error contracts much
// faster than σ_k assumes (Tippe-Top, mapped sets: σ_τ ≈ 3000, while the sliding iterate
// converges in 3 iterations); there the a-posteriori bound of a linearly converging iteration,
// |Λ^{ν+1} - Λ*| ≤ q/(1 - q)|ΔΛ^ν|, is used when it is smaller (a flat boundary, e.g. the side of
// C_F, keeps q ≈ 1 - r̂_F Ĝ_iikk, which gives back σ_k). 2e_k bounds the distance of two points of
// the friction set (Λ^{ν+1} and, up to the change of Λ_N, Λ*): it matters where σ_k is
// astronomical, e.g. σ_τ = Ĝ_TT/(R̄²G_ττ) ≈ 1e15 for the Tippe-Top with R = 1e-9 m, where
// 2R̄ρ ≈ 2e-15 N m s is below tolerance_abs. The rule is the plain increment test wherever (46)
// and Gauss-Seidel step naturally (normal block, sticking friction block). s_k also scales
// rounding errors: a tolerance_rel below about max_k s_k · 1e-15 may not be attainable.
// The reported residual is max_k d_k / (tolerance_abs + tolerance_rel·|Λ_k^{ν+1}|) of the last
// iteration (≤ 1 means converged; a term with a zero bound counts 0 if d_k = 0 and +inf
// otherwise); max_change is max_k |ΔΛ_k|, without s_k. Non-convergence is data: the solver
// returns after max_iterations with converged = false and never throws for it. If an iterate
// stops being finite (a divergent Jacobi iteration, e.g. α too large for strongly coupled
// contacts), the solver stops and returns the last finite iterate with converged = false and
// residual = max_change = +inf.
//
// Contacts with ball sets (sphere, ellipsoid, coulomb; kDirectSolveAfter): where the iteration
// creeps (a drilling stick/slip transition: Ĝ_ττ ~1e-6 Ĝ_TT, the natural step along τ leaves the
// set and the step r̂_F barely moves Λ̂_τ) each contact's inclusion is solved directly — a
// trust-region subproblem for the friction block inside a root search on Λ_N
// (ball_contact_solve.h) — one contact at once, several by block Gauss-Seidel sweeps (at most 200,
// until Λ̂ changes by less than 1e-13 of its size); the iteration goes on from that solution, so
// that `converged` keeps its meaning: the stopping rule above passed. The sweeps do not remove the
// drift of a statically indeterminate support (three or more contacts on one body can share the
// load in many ways): such islands can still end unconverged.
#ifndef NONSMOOTH_SIM_CORE_CONTACT_SOLVER_H_
#define NONSMOOTH_SIM_CORE_CONTACT_SOLVER_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nonsmooth_sim/core/friction_law.h"

namespace nonsmooth_sim {

/// Solver iteration scheme.
enum class SolverType { kJacobi, kModifiedJacobi, kGaussSeidel };
inline constexpr std::array<SolverType, 3> kAllSolverTypes = {
    SolverType::kJacobi, SolverType::kModifiedJacobi, SolverType::kGaussSeidel};
/// "jacobi", "modified_jacobi", "gauss_seidel"; "" for a value not in kAllSolverTypes.
std::string_view SolverTypeName(SolverType type);
std::optional<SolverType> SolverTypeFromName(std::string_view name);
std::string SolverTypeNameList();

/// Upper bound of SolverOptions::max_iterations for one ContactSolver::Solve: the iteration cap is
/// the solver's work multiplier (each iteration costs O(n²)), so a finite cap alone does not bound
/// a call (2^31 - 1 iterations of one Tippe-Top contact take 95 s or more: 44 ns each with
/// Gauss-Seidel, Release, an idle core, bounded_work_test, 2026-12-02). 1e6 is the largest cap the
/// converged reference solutions of single problems in the tests use; a Simulator, which solves
/// every step, has the tighter kMaxSimulatorIterations (simulator.h).
inline constexpr int kMaxSolverIterations = 1000000;
/// With SolverOptions::direct_solve, a problem whose contacts all have a friction set that is a
/// ball up to a diagonal map (sphere, ellipsoid, coulomb) and whose iteration has not converged
/// after this many iterations is solved directly (ball_contact_solve.h; several contacts, with
/// kGaussSeidel only, by block Gauss-Seidel sweeps, each contact solved directly) and the
/// iteration restarted from that
/// solution, within the same max_iterations. Above every converging solve of the shipped scenes (at most 91 iterations, the
/// rattleback, 8 s runs with sphere): where the iteration converges it is unchanged.
inline constexpr int kDirectSolveAfter = 100;
// Even: after an even number of iterations the iteration's two change buffers are where a call
// that continues it expects them, so a problem the direct solve cannot take (B_F, C_F) continues
// bit for bit as the uninterrupted iteration would.
static_assert(kDirectSolveAfter % 2 == 0);

/// Smallest SolverOptions::relaxation α. Without the prox, a component k moves by α/Ĝ_kk·ξ̂_k, so
/// on a decoupled contact the error contracts by |1 - α| per iteration and reaching a relative
/// tolerance τ takes about ln(1/τ)/α iterations: 1.2e4 for τ = 1e-5 at α = 1e-3, twelve times the
/// default cap. Smaller α only buys non-convergence, or worse, a stopping rule fooled by steps
/// that round to zero (α = 4.9e-324 moves nothing). The smallest α any scene needed: 0.05
/// (modified Jacobi on 12 coupled feet, docs/settings.md). The upper end stays open, α < 2, the
/// convergence interval of (43)/(46).
inline constexpr double kMinRelaxation = 1e-3;

/// Defaults (chosen on the Tippe-Top at Δt = 1e-4, warm-started by the Simulator): Gauss-Seidel
/// converges where the Jacobi schemes need α < 1 (two or more coupled contacts in stick, e.g. a
/// block on four feet), and tolerance_rel = 1e-5 reproduces every event time of a 1e-12 run to the
/// step (θ after 8 s within 3e-7 rad) at 3.7 iterations per step.
struct SolverOptions {
  SolverType type = SolverType::kGaussSeidel;
  double tolerance_rel = 1e-5;  ///< relative tolerance on the change of Λ, finite, ≥ 0
  double tolerance_abs = 1e-14; ///< absolute tolerance on the change of Λ [N s], finite, ≥ 0
  /// in [1, kMaxSolverIterations]; in a Simulator [1, kMaxSimulatorIterations]
  int max_iterations = 1000;
  double relaxation = 1.0;      ///< α of (43), in [kMinRelaxation, 2)
  /// Iterate `exact` and `cylinder` on A⁻¹D with A of (56), (40)-(47) (same solution, far fewer
  /// iterations when sliding); false = on the original sets (37), as the paper's B_F timing.
  /// `sphere` is always mapped, `ellipsoid` and `coulomb` never (see the table above).
  bool map_drilling_sets = true;
  /// Solve a problem of ball sets directly where the iteration has not converged after
  /// kDirectSolveAfter iterations (ball_contact_solve.h, above); false = the iteration alone, as
  /// the paper's (studies of the iteration itself).
  bool direct_solve = true;
};

/// Throws std::invalid_argument naming the offending field and its allowed range.
void ValidateSolverOptions(const SolverOptions& options);

/// One closed contact in the problem: its law and where its components start in Λ, c and G.
struct ContactBlock {
  int offset = 0;  ///< index of Λ_N of this contact in the stacked vectors
  ContactLaw law;  ///< dimension = ContactDimension(law)
};

/// The inclusion (17) for the closed contacts of one step. Components of contact i occupy
/// [offset_i, offset_i + dim_i) in order (N, T1, T2, τ); the contacts are stored in order and
/// without gaps (offset_0 = 0, offset_{i+1} = offset_i + dim_i, n = Σ dim_i).
struct ContactProblem {
  Eigen::MatrixXd G;  ///< Delassus matrix, symmetric positive semi-definite, n × n
  Eigen::VectorXd c;  ///< n
  std::vector<ContactBlock> contacts;
};

/// The same inclusion (17) in padded 4 × 4 blocks, the form the Simulator assembles straight from
/// W and M⁻¹ (no dense matrix, no offsets): contact i has the law `laws[i]`, c_i = c[i] and
/// G_ij = G[i·m + j] (row-major over the m contacts); the entries of a block beyond the contacts'
/// dimensions (ContactDimension) are ignored, as are those of c_i and of the warm start.
struct BlockContactProblem {
  std::vector<ContactLaw> laws;
  std::vector<Eigen::Matrix4d> G;  ///< m × m blocks, symmetric: G[j·m + i] = G[i·m + j]ᵀ
  std::vector<Eigen::Vector4d> c;
  int size() const { return static_cast<int>(laws.size()); }
  /// m contacts; allocates only when m exceeds every earlier size
  void Resize(int m);
};

/// Throws std::invalid_argument unless: the contacts are laid out as ContactProblem says, G is
/// n × n and c has n entries, every entry is finite, every diagonal entry of G is > 0 (a zero
/// diagonal means a force direction that moves nothing), and every law has finite μ ≥ 0 and
/// R̄ ≥ 0. Cost O(n²); no allocation. Symmetry and semi-definiteness are not checked.
void ValidateContactProblem(const ContactProblem& problem);

struct SolverStatistics {
  int iterations = 0;
  double residual = 0.0;  ///< max_k d_k / bound_k, see the stopping rule above; ≤ 1 when converged
  /// max_k |Λ_k^{ν+1} - Λ_k^ν| of the last iteration, not d_k [N s or N m s]; +inf only if it
  /// diverged.
  double max_change = 0.0;
  bool converged = false;
  /// Per contact: whether the last iteration projected its friction components (sliding) and its
  /// normal component (separating, Λ_N clamped to 0). Frictionless contacts: friction false.
  /// Bytes (0 or 1), not std::vector<bool>: written per contact every step, and a bit vector's
  /// masked writes cost the Tippe-Top about 2 % of its step.
  std::vector<std::uint8_t> friction_projected;
  std::vector<std::uint8_t> normal_projected;
};

namespace internal {
/// Per-contact data of ContactSolver's iteration, derived once per Solve from the problem and the
/// options, plus the contact's projection flags of the last iteration. Not part of the API.
struct ContactWork {
  Eigen::Vector4d scale = Eigen::Vector4d::Ones();  ///< diagonal of A_i (N, T1, T2, τ), see above
  Eigen::Vector4d step = Eigen::Vector4d::Zero();   ///< α / Ĝ_iikk (46); 0 where absent
  Eigen::Vector4d tolerance_abs_hat = Eigen::Vector4d::Zero();  ///< tolerance_abs / diag(A_i)
  /// σ_k of the stopping rule for the steps r̂_i of (43): (α/Ĝ_iikk) / r̂_i; 1 where absent
  Eigen::Vector4d change_scale_contact = Eigen::Vector4d::Ones();
  /// σ_k for (46) when the friction block stepped r̂_F (Q = I): (1, (α/Ĝ_iikk) / r̂_F for k ∈ F)
  Eigen::Vector4d change_scale_friction = Eigen::Vector4d::Ones();
  double r_contact = 0.0;   ///< r̂_i of (43): α / max_k Ĝ_iikk over the whole contact
  double r_normal = 0.0;    ///< α / Ĝ_iiNN: (46) on the normal block
  double r_friction = 0.0;  ///< α / max_{k∈F} Ĝ_iikk: (46) on the friction block
  double mu = 0.0;
  /// R̄ of the friction set in the iterated coordinates: R̄/a_τ, i.e. the law's R̄ on an original
  /// set (37) and 1 on A⁻¹B_F, A⁻¹C_F (40); unused by sphere (S_F) and the disk
  double set_rbar = 0.0;
  /// the last foot point of B_F's exact prox on its branch u > 1 (v = 1/u), NaN before the first:
  /// the warm start of the next (ProxCoulombContensou); from SolvePrevalidated's `rim_hints`
  double rim_hint = 0.0;
  int dim = 1;
  FrictionSet set = kPlanarFrictionSet;  ///< kPlanarFrictionSet for every 3-component contact
  bool normal_projected = false;
  bool friction_projected = false;
  /// (46): the last iteration accepted the friction block's per-component step y (s_k = 1)
  bool friction_natural_step = false;
};
}  // namespace internal

/// Solves (17). `lambda` holds the warm start on entry (size n; zeros if unknown) and the
/// solution on return. Allocates only when the problem grows beyond what an earlier call saw:
/// keep one ContactSolver per simulation.
class ContactSolver {
 public:
  /// Throws std::invalid_argument for invalid options (ValidateSolverOptions), an invalid problem
  /// (ValidateContactProblem), a null `lambda`, or a warm start of the wrong size or not finite.
  SolverStatistics Solve(const ContactProblem& problem, const SolverOptions& options,
                         Eigen::VectorXd* lambda);
  /// The same, filling `statistics` in place: with a statistics object reused across calls this
  /// overload does not allocate at all once the sizes have been seen.
  void Solve(const ContactProblem& problem, const SolverOptions& options, Eigen::VectorXd* lambda,
             SolverStatistics* statistics);
  /// The same without the checks, for a caller whose problems satisfy ValidateContactProblem by
  /// construction and whose options were validated once (the Simulator: G_ii > 0 for every
  /// contact on a body, c checked finite, Λ its own warm start). Bad input is undefined here.
  void SolvePrevalidated(const ContactProblem& problem, const SolverOptions& options,
                         Eigen::VectorXd* lambda, SolverStatistics* statistics);
  /// The same on the block form: `lambda` holds one padded Λ_i per contact (size m; the warm
  /// start on entry, the solution on return, zero beyond the contact's dimension). The problem
  /// must satisfy what ValidateContactProblem asks of the equivalent dense problem.
  /// `rim_hints` (optional, size m, in/out) warm-starts the exact prox of B_F per contact as
  /// `lambda` warm-starts Λ: ContactWork::rim_hint on entry (NaN for none), its last value on
  /// return. It changes only where the prox's 1-D solve starts, not what it finds.
  void SolvePrevalidated(const BlockContactProblem& problem, const SolverOptions& options,
                         std::vector<Eigen::Vector4d>* lambda, SolverStatistics* statistics,
                         std::vector<double>* rim_hints = nullptr);
  /// The same for a problem of one contact (m = 1: G its 4 × 4 block, c, its law), without
  /// the block problem's vectors: the same iteration, the same result to the last bit. Its
  /// projection flags are statistics->normal_projected[0] and friction_projected[0] (sized to
  /// 1 if empty, left longer if they are).
  void SolveOnePrevalidated(const Eigen::Matrix4d& G, const Eigen::Vector4d& c,
                            const ContactLaw& law, const SolverOptions& options,
                            Eigen::Vector4d* lambda, SolverStatistics* statistics,
                            double* rim_hint = nullptr);

 private:
  // kSingle: the problem has one contact (m = 1 known at compile time: no loops over j)
  template <SolverType kType, bool kSingle>
  void Iterate(const SolverOptions& options, int max_iterations, SolverStatistics* statistics);
  void Prepare(const BlockContactProblem& problem, const SolverOptions& options,
               const std::vector<Eigen::Vector4d>& lambda, const std::vector<double>* rim_hints);
  // Prepare's parts for contact i: its law's data, ĉ_i and Λ̂_i; and, once Ĝ_ii is known, its
  // steps and stopping-rule scales
  void PrepareContact(std::size_t i, const ContactLaw& law, const SolverOptions& options,
                      const Eigen::Vector4d& c, const Eigen::Vector4d& lambda, double rim_hint);
  void PrepareSteps(std::size_t i, const Eigen::Matrix4d& g_hat_ii, const SolverOptions& options);
  // Iterate for `options.type`, at most `max_iterations` (options.max_iterations unless the direct
  // solve splits the budget); m = 1 with kSingle
  template <bool kSingle>
  void IterateOf(const SolverOptions& options, int max_iterations, SolverStatistics* statistics);
  // IterateOf<true> for the one contact, with the direct solve (ball_contact_solve.h) where the
  // iteration has not converged after kDirectSolveAfter iterations and the set allows it
  void IterateOne(const SolverOptions& options, SolverStatistics* statistics);
  // IterateOne's rare part: the direct solve and the rest of the budget
  void ContinueDirectly(const SolverOptions& options, SolverStatistics* statistics);
  // The same for several contacts: block Gauss-Seidel sweeps, each contact solved directly
  void ContinueBlockDirectly(const SolverOptions& options, SolverStatistics* statistics);
  void ResizeWorkspace(std::size_t m);

  // workspace reused across calls: padded 4 × 4 blocks Ĝ_ij (row-major over contacts), ĉ_i, the
  // iterates Λ̂_i^ν and Λ̂_i^{ν+1}, and the last two changes |Λ̂_i^{ν+1} - Λ̂_i^ν| per contact
  // (std::vector suffices for the fixed-size Eigen types: C++17 honours their alignment)
  std::vector<internal::ContactWork> work_;
  std::vector<Eigen::Matrix4d> g_hat_;
  std::vector<Eigen::Vector4d> c_hat_, lambda_hat_, lambda_next_, change_, previous_change_;
  // a dense ContactProblem and its Λ in block form (the dense overloads only)
  BlockContactProblem blocks_;
  std::vector<Eigen::Vector4d> block_lambda_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_CONTACT_SOLVER_H_
