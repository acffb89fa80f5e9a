// The contact laws: one table, one row per friction set, that every part of the step reads.
//
// Möller, Leine, Glocker (ESMC 2009), section 6. A row names the set and says what the solver
// (contact_solver.h) needs to know about it:
//
//   name       set                     drilling  prox                  coordinates  ball     warm
//   coulomb    disk ||Λ_T|| ≤ μΛ_N     no        ProxDisk, Λ_τ = 0     original     I        Λ
//   cylinder   C_F (54)                yes       ProxCylinder          by option    -        Λ
//   ellipsoid  E_F (55)                yes       ProxEllipsoid         original     (1,1,R̄) Λ
//   sphere     S_F = A⁻¹E_F (57)-(59)  yes       ProxBall              mapped (56)  I        Λ
//   exact      B_F (51)-(53)           yes       ProxCoulombContensou  by option    -        Λ, rim
//   rolling    E_R, 5-D ellipsoid      yes       ProxBall; 5-D:        mapped (56)  I        Λ
//              (prox_rolling.h)                  ProxRollingBall
//   rolling_   E_F × rolling disk      yes       ProxBall; 5-D:        mapped (56)  I        Λ
//   decoupled  (prox_rolling.h)                  ProxRollingDecoupled
//
//  - drilling: whether a contact with μ > 0 and R̄ > 0 has the drilling component Λ_τ (4
//    components); without it a contact is 3-component and every law is the coulomb disk there.
//  - prox (force_sets.h): the exact Euclidean projection onto the set in the coordinates it is
//    iterated in, prox(z, radius = μΛ_N, set_rbar = R̄ of the iterated set, hint = its warm start).
//  - coordinates: the diagonal map A of (56) the solver iterates in, Λ̂ = A⁻¹Λ (40)-(47)
//    (transformation.h, ContactMapDiagonal); "by option": with SolverOptions::map_drilling_sets
//    (A⁻¹B_F = B_F, A⁻¹C_F = C_F with R̄ = 1), on the original set (37) without it.
//  - ball (metric): D with the iterated set = {||D⁻¹Λ̂_F|| ≤ μΛ̂_N}, if it is a ball up to a
//    diagonal map: such contacts can be solved directly (ball_contact_solve.h); R̄ is set_rbar.
//  - warm (start): what a contact carries from one step to the next besides its percussion Λ: B_F's
//    prox also its last foot point, the rim hint (ProxCoulombContensou's rim_hint).
//  - rolling: the two rows with rolling resistance (a rolling torque about t1, t2 bounded by
//    μ_rΛ_N). Their 5-D set (T1, T2, τ, R1, R2) applies where a contact has μ_r > 0 (prox5, in the
//    coordinates A = diag(1, 1, 1, R̄, μ_r/μ, μ_r/μ)); without rolling components (μ_r = 0) the
//    row is its 3-D part, S_F, and the contact is iterated exactly as `sphere`'s.
//
// A new law: its prox in a file pair of its own (declared in a header this file includes), one
// enum value and one row here, and a test of its prox (docs/building.md).
#ifndef NONSMOOTH_SIM_CORE_FRICTION_LAW_H_
#define NONSMOOTH_SIM_CORE_FRICTION_LAW_H_

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "nonsmooth_sim/core/force_sets.h"
#include "nonsmooth_sim/core/prox_rolling.h"

namespace nonsmooth_sim {

/// The friction laws of a contact (the rows of kFrictionLaws, in this order). Their names
/// (FrictionSetName) are the ones used everywhere: command line, ROS parameters and services,
/// URDF, benchmark JSON.
enum class FrictionSet {
  kCoulomb,    ///< "coulomb": planar Coulomb disk ||Λ_T|| ≤ μΛ_N, no drilling component.
  kCylinder,   ///< "cylinder": C_F (54), drilling decoupled from sliding.
  kEllipsoid,  ///< "ellipsoid": E_F (55), prox on the ellipsoid itself (37).
  kSphere,     ///< "sphere": E_F solved through the map A (56) onto the ball S_F (58), (40)-(47).
  kExact,      ///< "exact": the Coulomb-Contensou set B_F (51)-(53).
  kRolling,    ///< "rolling": E_F and the rolling torque in one 5-D ellipsoid, mapped to the ball.
  kRollingDecoupled,  ///< "rolling_decoupled": E_F mapped to S_F, the rolling torque on its disk.
};

inline constexpr std::array<FrictionSet, 7> kAllFrictionSets = {
    FrictionSet::kCoulomb, FrictionSet::kCylinder,          FrictionSet::kEllipsoid,
    FrictionSet::kSphere,  FrictionSet::kExact,             FrictionSet::kRolling,
    FrictionSet::kRollingDecoupled};

/// The law every contact without a drilling component is iterated with.
inline constexpr FrictionSet kPlanarFrictionSet = FrictionSet::kCoulomb;

/// The force law of one contact.
struct ContactLaw {
  double mu = 0.3;           ///< friction coefficient, ≥ 0; 0 = frictionless (no tangential part)
  double rbar = 0.0;         ///< average friction radius R̄ = 3πR/16 (50) [m], ≥ 0; 0 = no drilling
  double restitution = 0.0;  ///< Newton's ε (14), in [0, 1]
  FrictionSet friction_set = FrictionSet::kSphere;
  /// μ_r, the rolling-resistance length [m], finite, ≥ 0; 0 = no rolling components. A float in
  /// the padding after friction_set (relative rounding ≤ 6e-8): as a double it made the struct
  /// 40 bytes, and its copies cost the step 1.2 % more instructions.
  float rolling_resistance = 0.0f;
};
static_assert(sizeof(ContactLaw) == 32, "ContactLaw: keep μ_r in the padding");

/// The coordinates a law's set is iterated in (the table above).
enum class LawCoordinates {
  kOriginal,         ///< the set itself, (37)
  kMapped,           ///< A⁻¹ of the set with A of (56), (40)-(47)
  kMappedByOption,   ///< kMapped with SolverOptions::map_drilling_sets, kOriginal without
};

/// The friction set in the iterated coordinates as a ball {||D⁻¹Λ̂_F|| ≤ μΛ̂_N}, if it is one.
enum class BallMetric {
  kNone,            ///< not a ball up to a diagonal map (B_F, C_F)
  kUnit,            ///< D = I: the disk, S_F
  kDrillingRadius,  ///< D = diag(1, 1, R̄) (R̄ of the iterated set): E_F
};

/// What a contact of the law carries to the next step's solve.
enum class WarmStartKind {
  kPercussion,             ///< Λ
  kPercussionAndRimHint,   ///< Λ and B_F's last foot point (ProxCoulombContensou's rim_hint)
};

/// prox onto the 3-D friction set (T1, T2, τ): radius = μΛ_N [N s], set_rbar = R̄ of the iterated
/// set [m], hint = the law's warm start (in/out; not null for kPercussionAndRimHint, unused
/// otherwise).
using FrictionProx = Prox3 (*)(const Eigen::Vector3d& z, double radius, double set_rbar,
                               double* hint);

/// How a law bounds the rolling torque (Λ_R1, Λ_R2) where a contact has μ_r > 0.
enum class RollingKind {
  kNone,       ///< no rolling components: μ_r is ignored
  kCoupled,    ///< one 5-D ellipsoid with sliding and drilling (ProxRollingBall when mapped)
  kDecoupled,  ///< its own disk ||Λ_R|| ≤ μ_rΛ_N beside E_F (ProxRollingDecoupled when mapped)
};

/// prox onto the 5-D friction set (T1, T2, τ, R1, R2) in the mapped coordinates, radius = μΛ_N.
using FrictionProx5 = Prox5 (*)(const Vector5d& z, double radius);

/// One row of the laws table.
struct FrictionLaw {
  FrictionSet set;
  std::string_view name;
  std::string_view description;  ///< one line, for listings
  bool drilling;                 ///< has the drilling component Λ_τ
  FrictionProx prox;
  LawCoordinates coordinates;
  BallMetric ball_metric;
  WarmStartKind warm_start;
  RollingKind rolling;
  FrictionProx5 prox5;  ///< the 5-D set's prox where rolling ≠ kNone, else null
};

namespace law_prox {
// The prox functions of force_sets.h in the one signature FrictionProx (inlined where the solver
// calls them).
[[gnu::always_inline]] inline Prox3 PlanarDisk(const Eigen::Vector3d& z, double radius, double,
                                               double*) {
  const Prox2 disk = ProxDisk(z.head<2>(), radius);
  return {Eigen::Vector3d(disk.point.x(), disk.point.y(), 0.0), disk.region};
}
[[gnu::always_inline]] inline Prox3 Cylinder(const Eigen::Vector3d& z, double radius,
                                             double set_rbar, double*) {
  return ProxCylinder(z, radius, set_rbar);
}
[[gnu::always_inline]] inline Prox3 Ellipsoid(const Eigen::Vector3d& z, double radius,
                                              double set_rbar, double*) {
  return ProxEllipsoid(z, radius, set_rbar);
}
[[gnu::always_inline]] inline Prox3 Ball(const Eigen::Vector3d& z, double radius, double,
                                         double*) {
  return ProxBall(z, radius);
}
[[gnu::always_inline]] inline Prox3 CoulombContensou(const Eigen::Vector3d& z, double radius,
                                                     double set_rbar, double* rim_hint) {
  return ProxCoulombContensou(z, radius, set_rbar, rim_hint);
}
}  // namespace law_prox

/// The laws table, one row per FrictionSet in the enum's order.
inline constexpr std::array<FrictionLaw, kAllFrictionSets.size()> kFrictionLaws = {{
    {FrictionSet::kCoulomb, "coulomb", "planar Coulomb disk, no drilling friction",
     /*drilling=*/false, &law_prox::PlanarDisk, LawCoordinates::kOriginal, BallMetric::kUnit,
     WarmStartKind::kPercussion, RollingKind::kNone, nullptr},
    {FrictionSet::kCylinder, "cylinder", "cylinder C_F (54): drilling decoupled from sliding",
     /*drilling=*/true, &law_prox::Cylinder, LawCoordinates::kMappedByOption, BallMetric::kNone,
     WarmStartKind::kPercussion, RollingKind::kNone, nullptr},
    {FrictionSet::kEllipsoid, "ellipsoid", "ellipsoid E_F (55), iterated on itself (37)",
     /*drilling=*/true, &law_prox::Ellipsoid, LawCoordinates::kOriginal,
     BallMetric::kDrillingRadius, WarmStartKind::kPercussion, RollingKind::kNone, nullptr},
    {FrictionSet::kSphere, "sphere", "E_F iterated as the ball S_F through the map (56)",
     /*drilling=*/true, &law_prox::Ball, LawCoordinates::kMapped, BallMetric::kUnit,
     WarmStartKind::kPercussion, RollingKind::kNone, nullptr},
    {FrictionSet::kExact, "exact", "Coulomb-Contensou set B_F (51)-(53)",
     /*drilling=*/true, &law_prox::CoulombContensou, LawCoordinates::kMappedByOption,
     BallMetric::kNone, WarmStartKind::kPercussionAndRimHint, RollingKind::kNone, nullptr},
    {FrictionSet::kRolling, "rolling",
     "E_F and rolling torque <= mu_r*lambda_N in one 5-D ellipsoid, mapped to the ball",
     /*drilling=*/true, &law_prox::Ball, LawCoordinates::kMapped, BallMetric::kUnit,
     WarmStartKind::kPercussion, RollingKind::kCoupled, &ProxRollingBall},
    {FrictionSet::kRollingDecoupled, "rolling_decoupled",
     "S_F and, on its own disk, rolling torque <= mu_r*lambda_N",
     /*drilling=*/true, &law_prox::Ball, LawCoordinates::kMapped, BallMetric::kUnit,
     WarmStartKind::kPercussion, RollingKind::kDecoupled, &ProxRollingDecoupled},
}};

/// Whether the table's rows follow the enum (row i is the law of value i).
constexpr bool RowsFollowTheEnum() {
  for (std::size_t i = 0; i < kFrictionLaws.size(); ++i) {
    if (kFrictionLaws[i].set != kAllFrictionSets[i] || static_cast<std::size_t>(
                                                           kAllFrictionSets[i]) != i) {
      return false;
    }
  }
  return true;
}
static_assert(RowsFollowTheEnum(), "kFrictionLaws: one row per FrictionSet, in the enum's order");

/// Whether `set` is one of kAllFrictionSets (an enum holds any int).
constexpr bool IsFrictionSet(FrictionSet set) {
  return static_cast<std::size_t>(set) < kFrictionLaws.size();
}

/// The row of `set`. Precondition: IsFrictionSet(set).
constexpr const FrictionLaw& LawOf(FrictionSet set) {
  return kFrictionLaws[static_cast<std::size_t>(set)];
}

/// The row's name, e.g. "sphere". Precondition: IsFrictionSet(set).
constexpr std::string_view FrictionSetName(FrictionSet set) { return LawOf(set).name; }
/// Inverse of FrictionSetName(); std::nullopt for an unknown name.
std::optional<FrictionSet> FrictionSetFromName(std::string_view name);
/// The names, comma-separated (for error messages).
std::string FrictionSetNameList();

/// Bit i set where row i's field equals kValue.
template <auto kField, auto kValue>
constexpr unsigned MakeLawMask() {
  static_assert(kFrictionLaws.size() <= 32);
  unsigned mask = 0;
  for (std::size_t i = 0; i < kFrictionLaws.size(); ++i) {
    if (kFrictionLaws[i].*kField == kValue) mask |= 1u << i;
  }
  return mask;
}

/// LawOf(set).*kField == kValue, e.g. LawIs<&FrictionLaw::drilling, true>(set), read from a bit
/// mask of the table (one or two instructions: the form the step's per-contact code uses).
/// Precondition: IsFrictionSet(set).
template <auto kField, auto kValue>
constexpr bool LawIs(FrictionSet set) {
  constexpr unsigned kMask = MakeLawMask<kField, kValue>();
  return ((kMask >> static_cast<unsigned>(set)) & 1u) != 0;
}

/// Number of percussion components a contact with this law has: 1 (frictionless, μ = 0), 3 (normal
/// and two tangential: a law without drilling, or R̄ = 0) or 4 (with the drilling component).
/// Inline: the step asks it several times per contact.
inline int ContactDimension(const ContactLaw& law) {
  if (!(law.mu > 0.0)) return 1;
  if (LawIs<&FrictionLaw::drilling, false>(law.friction_set) || !(law.rbar > 0.0)) return 3;
  return 4;
}

/// Whether a contact with this law has the rolling components (Λ_R1, Λ_R2): μ > 0, R̄ > 0,
/// μ_r > 0 and a row with rolling (RollingKind ≠ kNone). Such a contact has 6 components
/// (N, T1, T2, τ, R1, R2), solved by RollingContactSolver (rolling_contact_solver.h).
inline bool HasRolling(const ContactLaw& law) {
  return law.rolling_resistance > 0.0f && ContactDimension(law) == 4 &&
         !LawIs<&FrictionLaw::rolling, RollingKind::kNone>(law.friction_set);
}

/// ContactDimension, or 6 where the contact has rolling components (HasRolling).
inline int ContactDimensionWithRolling(const ContactLaw& law) {
  return HasRolling(law) ? 6 : ContactDimension(law);
}

namespace law_detail {
// Row kRow's prox; rows beyond the table are never reached (ProxFrictionLaw's precondition).
template <std::size_t kRow>
[[gnu::always_inline]] inline Prox3 ProxOfRow(const Eigen::Vector3d& z, double radius,
                                              double set_rbar, double* hint) {
  if constexpr (kRow < kFrictionLaws.size()) {
    constexpr FrictionProx prox = kFrictionLaws[kRow].prox;
    return prox(z, radius, set_rbar, hint);
  } else {
    __builtin_unreachable();
  }
}
}  // namespace law_detail

/// The prox of `set`'s row (FrictionLaw::prox), dispatched so that the row's function is inlined
/// (the solver calls it once per contact and iteration): a switch over the row index, which the
/// compiler turns into one jump. Precondition: IsFrictionSet(set).
[[gnu::always_inline]] inline Prox3 ProxFrictionLaw(FrictionSet set, const Eigen::Vector3d& z,
                                                    double radius, double set_rbar,
                                                    double* hint) {
  static_assert(kFrictionLaws.size() <= 8, "ProxFrictionLaw: add cases for the new rows");
  switch (static_cast<std::size_t>(set)) {
    case 0: return law_detail::ProxOfRow<0>(z, radius, set_rbar, hint);
    case 1: return law_detail::ProxOfRow<1>(z, radius, set_rbar, hint);
    case 2: return law_detail::ProxOfRow<2>(z, radius, set_rbar, hint);
    case 3: return law_detail::ProxOfRow<3>(z, radius, set_rbar, hint);
    case 4: return law_detail::ProxOfRow<4>(z, radius, set_rbar, hint);
    case 5: return law_detail::ProxOfRow<5>(z, radius, set_rbar, hint);
    case 6: return law_detail::ProxOfRow<6>(z, radius, set_rbar, hint);
    case 7: return law_detail::ProxOfRow<7>(z, radius, set_rbar, hint);
  }
  __builtin_unreachable();
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_FRICTION_LAW_H_
