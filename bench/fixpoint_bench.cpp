// Cost of one converged fixed-point solve of the contact inclusion (17) per friction law.
//
// Problems: a fixed collection of Tippe-Top contact problems (one step, Δt = 1e-4 s) built here
// from the geometry of ../shared/reference/tippe-top.md: m = 6e-3 kg, Θ_S = diag(8, 8, 7)·1e-7
// kg m², big sphere R1 = 15 mm at a1 = 3 mm from S along e3, peg R2 = 5 mm at a2 = 16 mm, μ = 0.3,
// R = 0.5 mm (R̄ = 3πR/16 (50)), g = 9.81 m/s², ε = 0. Velocities u = (v_S, ω) in the world
// frame, e3 tilted about the world x axis by θ:
//   1. big sphere, θ = 0.1, spin 180 rad/s about e3, S at rest: slides at 0.27 m/s, drills
//   2. big sphere, θ = 0.5, spin 180 rad/s, v_S = (0.05, 0, 0) m/s: slides
//   3. big sphere, θ = 1.2, ω = 60 e3 + 3 ẑ rad/s: slides
//   4. big sphere, θ = 0.3, ω = (0.5, -0.3, 0) rad/s rolling (contact point at rest): sticks
//   5. both spheres (θ* = arccos((R1-R2)/(a1-a2)) ≈ 140°), spin 180 rad/s: both slide
//   6. both spheres at θ*, rolling about the line through both contact points at 0.5 rad/s:
//      both stick (8 components on 6 velocities: G is singular)
// Delassus matrix G = Wᵀ M⁻¹ W and c = Wᵀ(u + M⁻¹ h Δt) (16) with h = (m g, -ω × Θω); W per
// contact: N = ẑ, T1 = x̂, T2 = ŷ at the contact point and the drilling torque about ẑ (absent
// for coulomb). A small construction of its own (the simulator's lives in
// contact/contact_jacobian.h).
//
// Solver options, the same for every law: modified_jacobi (46), tolerance_rel = 1e-10,
// tolerance_abs = 1e-20 (only so that components converging to exactly 0 stop), relaxation
// α = 0.7 (< 2/2.65: the two-contact problems need it, see contact_solver.h "Convergence"),
// max_iterations = 100000, cold start Λ = 0. Every benchmark iteration is one solve, cycling
// through the six problems, so the time is the mean ns per converged solve. Counter
// "iterations": mean fixed-point iterations per solve. A solve that does not converge stops the
// benchmark with an error.
//
// Variants: BM_Fixpoint/<law> runs the default SolverOptions::map_drilling_sets = true (sphere,
// exact and cylinder iterated on A⁻¹D, (40)-(47); ellipsoid on E_F itself, (37)); exact_unmapped
// and cylinder_unmapped set it to false and iterate B_F and C_F on the original sets (37), as the
// paper's B_F timing.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/force_sets.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace {

using nonsmooth_sim::ContactBlock;
using nonsmooth_sim::ContactLaw;
using nonsmooth_sim::ContactProblem;
using nonsmooth_sim::ContactSolver;
using nonsmooth_sim::FrictionSet;
using nonsmooth_sim::SolverOptions;
using nonsmooth_sim::SolverStatistics;
using nonsmooth_sim::SolverType;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

constexpr double kMass = 6e-3;                 // m [kg]
constexpr double kInertiaEquatorial = 8e-7;    // A = B [kg m²]
constexpr double kInertiaAxial = 7e-7;         // C [kg m²]
constexpr double kBigRadius = 0.015;           // R1 [m]
constexpr double kBigOffset = 0.003;           // a1 [m]
constexpr double kPegRadius = 0.005;           // R2 [m]
constexpr double kPegOffset = 0.016;           // a2 [m]
constexpr double kMu = 0.3;
constexpr double kContactRadius = 5e-4;        // R [m]
constexpr double kGravity = 9.81;              // [m/s²]
constexpr double kTimeStep = 1e-4;             // Δt [s]

struct Sphere {
  double offset;  // along e3 from S [m]
  double radius;  // [m]
};
constexpr Sphere kBig{kBigOffset, kBigRadius};
constexpr Sphere kPeg{kPegOffset, kPegRadius};

// The body at inclination θ (e3 tilted about world x) with u = (v_S, ω) in the world frame.
struct Configuration {
  double inclination;
  std::vector<Sphere> touching;
  Eigen::Vector3d linear_velocity;
  Eigen::Vector3d angular_velocity;
};

Eigen::Matrix3d Orientation(double inclination) {
  return Eigen::AngleAxisd(inclination, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

// S → lowest point of the sphere, world frame
Eigen::Vector3d ContactArm(const Sphere& sphere, double inclination) {
  return sphere.offset * Orientation(inclination).col(2) - sphere.radius * Eigen::Vector3d::UnitZ();
}

ContactProblem MakeProblem(const Configuration& configuration, FrictionSet set) {
  ContactLaw law;
  law.mu = kMu;
  law.rbar = nonsmooth_sim::AverageFrictionRadius(kContactRadius);  // (50)
  law.friction_set = set;
  const int dim = nonsmooth_sim::ContactDimension(law);
  const int n = dim * static_cast<int>(configuration.touching.size());

  const Eigen::Matrix3d rotation = Orientation(configuration.inclination);
  const Eigen::Matrix3d inertia =
      rotation * Eigen::Vector3d(kInertiaEquatorial, kInertiaEquatorial, kInertiaAxial).asDiagonal() *
      rotation.transpose();
  Matrix6d m_inverse = Matrix6d::Zero();
  m_inverse.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / kMass;
  m_inverse.bottomRightCorner<3, 3>() = inertia.inverse();

  // W: N = ẑ, T1 = x̂, T2 = ŷ at the contact point, drilling torque about ẑ
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(6, n);
  ContactProblem problem;
  for (std::size_t i = 0; i < configuration.touching.size(); ++i) {
    const int offset = dim * static_cast<int>(i);
    problem.contacts.push_back(ContactBlock{offset, law});
    const Eigen::Vector3d arm = ContactArm(configuration.touching[i], configuration.inclination);
    const Eigen::Vector3d directions[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                           Eigen::Vector3d::UnitY()};
    for (int k = 0; k < 3; ++k) {
      w.block<3, 1>(0, offset + k) = directions[k];
      w.block<3, 1>(3, offset + k) = arm.cross(directions[k]);
    }
    if (dim == 4) w.block<3, 1>(3, offset + 3) = Eigen::Vector3d::UnitZ();
  }
  Vector6d u;
  u << configuration.linear_velocity, configuration.angular_velocity;
  const Eigen::Vector3d& omega = configuration.angular_velocity;
  Vector6d h;
  h << Eigen::Vector3d(0.0, 0.0, -kMass * kGravity), -omega.cross(inertia * omega);
  // (16) with ε = 0 and χ = 0: G = Wᵀ M⁻¹ W, c = Wᵀ(u + M⁻¹ h Δt)
  problem.G = w.transpose() * m_inverse * w;
  problem.c = w.transpose() * (u + m_inverse * h * kTimeStep);
  return problem;
}

std::vector<Configuration> Configurations() {
  const double both = std::acos((kBigRadius - kPegRadius) / (kBigOffset - kPegOffset));
  const auto spin = [](double inclination, double rate) -> Eigen::Vector3d {
    return rate * Orientation(inclination).col(2);
  };
  const auto rolling = [](double inclination, const Sphere& sphere,
                          const Eigen::Vector3d& omega) -> Eigen::Vector3d {
    // v_S = -ω × r_SP: the contact point is at rest
    return -omega.cross(ContactArm(sphere, inclination));
  };
  std::vector<Configuration> configurations;
  configurations.push_back({0.1, {kBig}, Eigen::Vector3d::Zero(), spin(0.1, 180.0)});
  configurations.push_back({0.5, {kBig}, Eigen::Vector3d(0.05, 0.0, 0.0), spin(0.5, 180.0)});
  configurations.push_back(
      {1.2, {kBig}, Eigen::Vector3d::Zero(), spin(1.2, 60.0) + Eigen::Vector3d(0.0, 0.0, 3.0)});
  const Eigen::Vector3d slow(0.5, -0.3, 0.0);
  configurations.push_back({0.3, {kBig}, rolling(0.3, kBig, slow), slow});
  configurations.push_back({both, {kBig, kPeg}, Eigen::Vector3d::Zero(), spin(both, 180.0)});
  // rolling about the line through both contact points
  const Eigen::Vector3d axis =
      0.5 * (ContactArm(kPeg, both) - ContactArm(kBig, both)).normalized();
  configurations.push_back({both, {kBig, kPeg}, rolling(both, kBig, axis), axis});
  return configurations;
}

SolverOptions BenchmarkOptions(bool map_drilling_sets) {
  SolverOptions options;
  options.map_drilling_sets = map_drilling_sets;
  options.type = SolverType::kModifiedJacobi;
  options.tolerance_rel = 1e-10;
  options.tolerance_abs = 1e-20;
  options.relaxation = 0.7;
  options.max_iterations = 100000;
  return options;
}

void BM_Fixpoint(benchmark::State& state, FrictionSet set, bool map_drilling_sets) {
  std::vector<ContactProblem> problems;
  for (const Configuration& configuration : Configurations()) {
    problems.push_back(MakeProblem(configuration, set));
  }
  std::vector<Eigen::VectorXd> lambdas;
  for (const ContactProblem& problem : problems) lambdas.emplace_back(problem.c.size());
  const SolverOptions options = BenchmarkOptions(map_drilling_sets);
  ContactSolver solver;
  SolverStatistics statistics;
  // one untimed pass: every problem must converge
  for (std::size_t i = 0; i < problems.size(); ++i) {
    lambdas[i].setZero();
    solver.Solve(problems[i], options, &lambdas[i], &statistics);
    if (!statistics.converged) {
      state.SkipWithError(("problem " + std::to_string(i + 1) + " did not converge").c_str());
      return;
    }
  }
  std::size_t i = 0;
  double iterations = 0.0;
  for (auto _ : state) {
    lambdas[i].setZero();
    solver.Solve(problems[i], options, &lambdas[i], &statistics);
    benchmark::DoNotOptimize(lambdas[i].data());
    iterations += statistics.iterations;
    i = i + 1 == problems.size() ? 0 : i + 1;
  }
  state.counters["iterations"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

// Names as in FrictionSetName(): BM_Fixpoint/coulomb, ..., BM_Fixpoint/exact (default options),
// plus BM_Fixpoint/exact_unmapped and BM_Fixpoint/cylinder_unmapped (map_drilling_sets = false).
BENCHMARK_CAPTURE(BM_Fixpoint, coulomb, FrictionSet::kCoulomb, true);
BENCHMARK_CAPTURE(BM_Fixpoint, cylinder, FrictionSet::kCylinder, true);
BENCHMARK_CAPTURE(BM_Fixpoint, ellipsoid, FrictionSet::kEllipsoid, true);
BENCHMARK_CAPTURE(BM_Fixpoint, sphere, FrictionSet::kSphere, true);
BENCHMARK_CAPTURE(BM_Fixpoint, exact, FrictionSet::kExact, true);
BENCHMARK_CAPTURE(BM_Fixpoint, exact_unmapped, FrictionSet::kExact, false);
BENCHMARK_CAPTURE(BM_Fixpoint, cylinder_unmapped, FrictionSet::kCylinder, false);

}  // namespace
