// Names of the enumerated choices, shared by the command line, ROS and benchmark output.
#include <string>

#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/force_sets.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

template <typename Enum, std::size_t N>
std::optional<Enum> FromName(std::string_view name, const std::array<Enum, N>& all,
                             std::string_view (*to_name)(Enum)) {
  for (Enum value : all) {
    if (to_name(value) == name) return value;
  }
  return std::nullopt;
}

template <typename Enum, std::size_t N>
std::string NameList(const std::array<Enum, N>& all, std::string_view (*to_name)(Enum)) {
  std::string list;
  for (Enum value : all) {
    if (!list.empty()) list += ", ";
    list += to_name(value);
  }
  return list;
}

constexpr std::array<SolverType, 3> kAllSolverTypes = {
    SolverType::kJacobi, SolverType::kModifiedJacobi, SolverType::kGaussSeidel};
constexpr std::array<GyroscopicScheme, 3> kAllGyroscopicSchemes = {
    GyroscopicScheme::kExplicit, GyroscopicScheme::kImplicitMidpoint, GyroscopicScheme::kAuto};
constexpr std::array<Integrator, 2> kAllIntegrators = {Integrator::kMoreau, Integrator::kMoreau2};

}  // namespace

std::string_view FrictionSetName(FrictionSet set) {
  switch (set) {
    case FrictionSet::kCoulomb: return "coulomb";
    case FrictionSet::kCylinder: return "cylinder";
    case FrictionSet::kEllipsoid: return "ellipsoid";
    case FrictionSet::kSphere: return "sphere";
    case FrictionSet::kExact: return "exact";
  }
  return "unknown";
}
std::optional<FrictionSet> FrictionSetFromName(std::string_view name) {
  return FromName(name, kAllFrictionSets, &FrictionSetName);
}
std::string FrictionSetNameList() { return NameList(kAllFrictionSets, &FrictionSetName); }

std::string_view SolverTypeName(SolverType type) {
  switch (type) {
    case SolverType::kJacobi: return "jacobi";
    case SolverType::kModifiedJacobi: return "modified_jacobi";
    case SolverType::kGaussSeidel: return "gauss_seidel";
  }
  return "unknown";
}
std::optional<SolverType> SolverTypeFromName(std::string_view name) {
  return FromName(name, kAllSolverTypes, &SolverTypeName);
}
std::string SolverTypeNameList() { return NameList(kAllSolverTypes, &SolverTypeName); }

std::string_view GyroscopicSchemeName(GyroscopicScheme scheme) {
  switch (scheme) {
    case GyroscopicScheme::kExplicit: return "explicit";
    case GyroscopicScheme::kImplicitMidpoint: return "implicit_midpoint";
    case GyroscopicScheme::kAuto: return "auto";
  }
  return "unknown";
}
std::optional<GyroscopicScheme> GyroscopicSchemeFromName(std::string_view name) {
  return FromName(name, kAllGyroscopicSchemes, &GyroscopicSchemeName);
}

std::string_view IntegratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::kMoreau: return "moreau";
    case Integrator::kMoreau2: return "moreau2";
  }
  return "unknown";
}
std::optional<Integrator> IntegratorFromName(std::string_view name) {
  return FromName(name, kAllIntegrators, &IntegratorName);
}

}  // namespace nonsmooth_sim
