// Cost of one proximal point evaluation for every friction set (force_sets.h).
//
// Inputs: 1024 friction percussions at Tippe-Top scale (Λ_N = 6e-6 N s, radius μΛ_N with μ = 0.3,
// R̄ = 2.945e-4 m), fixed seed. In the scaled meridian coordinates (||Λ_T||/radius,
// |Λ_τ|/(R̄·radius)) the even-numbered inputs lie in the quarter disk of radius 0.9 (inside every
// set: the cross-section of B_F lies between the radii 0.94 and 1 in these coordinates) and the
// odd-numbered ones at radius 1.1 to 3 (outside E_F, S_F and B_F; outside the disk and the
// cylinder when their tangential or drilling part is): about half the inputs are interior.
// Tangential direction and the sign of Λ_τ are random.
//
// "sphere" is the same input seen by the transformed iteration (43): A⁻¹x with A = diag(1, 1, R̄)
// (56), projected onto the ball S_F (58)-(59).
//
// Reported time = ns per single prox call: every benchmark iteration evaluates exactly one prox,
// cycling through the input array (the loop's own cost, an index increment and a
// DoNotOptimize, is included and below 1 ns).
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>

#include "nonsmooth_sim/core/friction_law.h"

namespace {

using nonsmooth_sim::FrictionSet;

constexpr double kNormalPercussion = 6e-6;  // Λ_N [N s]
constexpr double kMu = 0.3;
constexpr double kRadius = kMu * kNormalPercussion;  // μΛ_N [N s]
constexpr double kRbar = 2.945e-4;                   // R̄ [m]
constexpr std::size_t kInputCount = 1024;            // a power of 2 (index mask below)
constexpr double kHalfPi = 1.57079632679489661923;

std::array<Eigen::Vector3d, kInputCount> MakeInputs() {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::array<Eigen::Vector3d, kInputCount> inputs;
  for (std::size_t i = 0; i < kInputCount; ++i) {
    // scaled radius in the meridian plane: interior (even i) or exterior (odd i)
    const double r = (i % 2 == 0) ? 0.9 * unit(rng) : 1.1 + 1.9 * unit(rng);
    const double alpha = kHalfPi * unit(rng);      // direction in the meridian plane
    const double psi = 4.0 * kHalfPi * unit(rng);  // tangential direction
    const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
    const double tangential = kRadius * r * std::cos(alpha);
    inputs[i] = Eigen::Vector3d(tangential * std::cos(psi), tangential * std::sin(psi),
                                sign * kRbar * kRadius * r * std::sin(alpha));
  }
  return inputs;
}

const std::array<Eigen::Vector3d, kInputCount>& Inputs() {
  static const std::array<Eigen::Vector3d, kInputCount> inputs = MakeInputs();
  return inputs;
}

// The inputs as seen by the sphere law: A⁻¹x (56).
const std::array<Eigen::Vector3d, kInputCount>& SphereInputs() {
  static const std::array<Eigen::Vector3d, kInputCount> inputs = [] {
    std::array<Eigen::Vector3d, kInputCount> mapped = Inputs();
    for (Eigen::Vector3d& x : mapped) x.z() /= kRbar;
    return mapped;
  }();
  return inputs;
}

// One prox per iteration, cycling through the inputs.
template <class Prox>
void RunProx(benchmark::State& state, const std::array<Eigen::Vector3d, kInputCount>& inputs,
             Prox prox) {
  std::size_t i = 0;
  for (auto _ : state) {
    auto result = prox(inputs[i]);
    benchmark::DoNotOptimize(result);
    i = (i + 1) & (kInputCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_ProxCoulomb(benchmark::State& state) {
  RunProx(state, Inputs(),
          [](const Eigen::Vector3d& x) { return nonsmooth_sim::ProxDisk(x.head<2>(), kRadius); });
}
void BM_ProxCylinder(benchmark::State& state) {
  RunProx(state, Inputs(),
          [](const Eigen::Vector3d& x) { return nonsmooth_sim::ProxCylinder(x, kRadius, kRbar); });
}
void BM_ProxEllipsoid(benchmark::State& state) {
  RunProx(state, Inputs(),
          [](const Eigen::Vector3d& x) { return nonsmooth_sim::ProxEllipsoid(x, kRadius, kRbar); });
}
void BM_ProxSphere(benchmark::State& state) {
  RunProx(state, SphereInputs(),
          [](const Eigen::Vector3d& x) { return nonsmooth_sim::ProxBall(x, kRadius); });
}
void BM_ProxExact(benchmark::State& state) {
  RunProx(state, Inputs(), [](const Eigen::Vector3d& x) {
    return nonsmooth_sim::ProxCoulombContensou(x, kRadius, kRbar);
  });
}

// exact, warm-started (the overload with a hint) from the foot point this input gave the previous
// time round: the best case of a solver, whose iterates move a little between calls.
void BM_ProxExactWarm(benchmark::State& state) {
  static std::array<double, kInputCount> hints;
  hints.fill(std::nan(""));
  const std::array<Eigen::Vector3d, kInputCount>& inputs = Inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    auto result = nonsmooth_sim::ProxCoulombContensou(inputs[i], kRadius, kRbar, &hints[i]);
    benchmark::DoNotOptimize(result);
    i = (i + 1) & (kInputCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

// Names as in FrictionSetName(): BM_Prox/coulomb, ..., BM_Prox/exact.
BENCHMARK(BM_ProxCoulomb)->Name("BM_Prox/coulomb");
BENCHMARK(BM_ProxCylinder)->Name("BM_Prox/cylinder");
BENCHMARK(BM_ProxEllipsoid)->Name("BM_Prox/ellipsoid");
BENCHMARK(BM_ProxSphere)->Name("BM_Prox/sphere");
BENCHMARK(BM_ProxExact)->Name("BM_Prox/exact");
BENCHMARK(BM_ProxExactWarm)->Name("BM_Prox/exact_warm");

}  // namespace
