// Scene validation, the laws of collider pairs and the observables of a state.
#include "nonsmooth_sim/core/scene.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace nonsmooth_sim {
namespace {

// An inertia tensor read from a file or built in code is symmetric up to round-off of its
// entries; a larger asymmetry is an input error.
constexpr double kInertiaSymmetryTolerance = 1e-9;
// The neutral element of min(μ_a, μ_b): the body's μ decides, however large.
constexpr double kGroundFriction = std::numeric_limits<double>::max();
// A rotation read from a file is orthonormal up to round-off.
constexpr double kRotationTolerance = 1e-9;

std::string BodyName(const Scene& scene, std::size_t b) {
  std::ostringstream s;
  s << "scene.bodies[" << b << "]";
  if (!scene.bodies[b].name.empty()) s << " (" << scene.bodies[b].name << ")";
  return s.str();
}

std::string ColliderName(const Scene& scene, std::size_t i) {
  std::ostringstream s;
  s << "scene.colliders[" << i << "]";
  if (!scene.colliders[i].name.empty()) s << " (" << scene.colliders[i].name << ")";
  return s.str();
}

[[noreturn]] void Reject(const std::string& what, double value, const std::string& allowed) {
  std::ostringstream s;
  s << what << " = " << value << ": must be " << allowed;
  throw std::invalid_argument(s.str());
}

void RequireFinite(const std::string& what, const Eigen::Ref<const Eigen::MatrixXd>& value) {
  if (!value.allFinite()) throw std::invalid_argument(what + " must be finite (no NaN or inf)");
}

void ValidateInertia(const std::string& where, const Eigen::Matrix3d& inertia) {
  const std::string what = where + ".inertia";
  RequireFinite(what, inertia);
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > kInertiaSymmetryTolerance * scale) {
    throw std::invalid_argument(what + " must be symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  if (!(eigen.eigenvalues().minCoeff() > 0.0)) {
    Reject(what + " smallest eigenvalue", eigen.eigenvalues().minCoeff(),
           "> 0 (positive definite) [kg m^2]");
  }
}

void ValidateCollider(const Scene& scene, std::size_t i) {
  const Collider& collider = scene.colliders[i];
  const std::string where = ColliderName(scene, i);
  if (collider.name.empty()) throw std::invalid_argument(where + ".name must not be empty");
  if (collider.body != kWorld &&
      (collider.body < 0 || static_cast<std::size_t>(collider.body) >= scene.bodies.size())) {
    std::ostringstream s;
    s << where << ".body = " << collider.body << ": must index scene.bodies (in [0, "
      << scene.bodies.size() << ")) or be kWorld (-1)";
    throw std::invalid_argument(s.str());
  }
  RequireFinite(where + ".pose", collider.pose.matrix());
  const Eigen::Matrix3d r = collider.pose.linear();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() >
          kRotationTolerance ||
      !(r.determinant() > 0.0)) {
    throw std::invalid_argument(where + ".pose must be a rigid transform (rotation orthonormal)");
  }
  ValidateShape(collider.shape, where + ".shape");
  if (collider.shape.type == ShapeType::kPlane && collider.body != kWorld) {
    throw std::invalid_argument(where +
                                ".shape: a plane is a static half-space, it cannot be on a body");
  }
  ValidateLaw(where + ".law", collider.law);
}

}  // namespace

ContactLaw GroundLaw() {
  ContactLaw law;
  law.mu = kGroundFriction;
  law.rbar = 0.0;
  law.restitution = 0.0;
  law.rolling_resistance = std::numeric_limits<float>::max();
  return law;
}

Collider GroundPlane(const ContactLaw& law) {
  Collider ground;
  ground.name = "ground";
  ground.body = kWorld;
  ground.shape = Shape::Plane();
  ground.law = law;
  return ground;
}

int FindCollider(const Scene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    if (scene.colliders[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

void ValidateLaw(const std::string& where, const ContactLaw& law) {
  if (!(std::isfinite(law.mu) && law.mu >= 0.0)) Reject(where + ".mu", law.mu, "finite, >= 0");
  if (!(std::isfinite(law.rbar) && law.rbar >= 0.0)) {
    Reject(where + ".rbar", law.rbar, "finite, >= 0 [m]");
  }
  if (!(law.restitution >= 0.0 && law.restitution <= 1.0)) {
    Reject(where + ".restitution", law.restitution, "in [0, 1]");
  }
  if (!(std::isfinite(law.rolling_resistance) && law.rolling_resistance >= 0.0f)) {
    Reject(where + ".rolling_resistance", law.rolling_resistance, "finite, >= 0 [m]");
  }
  if (!IsFrictionSet(law.friction_set)) {
    throw std::invalid_argument(where + ".friction_set is not one of " + FrictionSetNameList());
  }
}

int AppendScene(const Scene& model, Scene* world) {
  const int first = static_cast<int>(world->bodies.size());
  world->bodies.insert(world->bodies.end(), model.bodies.begin(), model.bodies.end());
  world->initial_state.insert(world->initial_state.end(), model.initial_state.begin(),
                              model.initial_state.end());
  for (const Collider& collider : model.colliders) {
    world->colliders.push_back(collider);
    if (collider.body != kWorld) world->colliders.back().body += first;
  }
  return first;
}

void RemoveFromScene(const std::vector<char>& remove_body, const std::vector<char>& remove_collider,
                     Scene* world, std::vector<int>* body_map, std::vector<int>* collider_map) {
  Scene rest;
  rest.gravity = world->gravity;
  body_map->assign(world->bodies.size(), -1);
  for (std::size_t b = 0; b < world->bodies.size(); ++b) {
    if (remove_body[b]) continue;
    (*body_map)[b] = static_cast<int>(rest.bodies.size());
    rest.bodies.push_back(std::move(world->bodies[b]));
    if (b < world->initial_state.size()) rest.initial_state.push_back(world->initial_state[b]);
  }
  collider_map->assign(world->colliders.size(), -1);
  for (std::size_t i = 0; i < world->colliders.size(); ++i) {
    Collider& c = world->colliders[i];
    if (c.body == kWorld ? remove_collider[i] != 0
                         : remove_body[static_cast<std::size_t>(c.body)] != 0) {
      continue;
    }
    (*collider_map)[i] = static_cast<int>(rest.colliders.size());
    if (c.body != kWorld) c.body = (*body_map)[static_cast<std::size_t>(c.body)];
    rest.colliders.push_back(std::move(c));
  }
  *world = std::move(rest);
}

void ValidateScene(const Scene& scene) {
  if (scene.bodies.empty()) throw std::invalid_argument("scene.bodies must not be empty");
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const RigidBody& body = scene.bodies[b];
    const std::string where = BodyName(scene, b);
    if (!(std::isfinite(body.mass) && body.mass > 0.0)) {
      Reject(where + ".mass", body.mass, "finite, > 0 [kg]");
    }
    ValidateInertia(where, body.inertia);
    RequireFinite(where + ".com_in_link", body.com_in_link);
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    ValidateCollider(scene, i);
    if (!names.insert(scene.colliders[i].name).second) {
      throw std::invalid_argument(ColliderName(scene, i) +
                                  ".name is used twice (contacts are addressed by name)");
    }
  }
  RequireFinite("scene.gravity", scene.gravity);
  ValidateState(scene, scene.initial_state);
}

void ValidateState(const Scene& scene, const std::vector<BodyState>& state) {
  if (state.size() != scene.bodies.size()) {
    std::ostringstream s;
    s << "state has " << state.size() << " bodies: must have one per scene body ("
      << scene.bodies.size() << ")";
    throw std::invalid_argument(s.str());
  }
  for (std::size_t b = 0; b < state.size(); ++b) {
    std::ostringstream s;
    s << "state[" << b << "]";
    const std::string where = s.str();
    RequireFinite(where + ".position", state[b].position);
    RequireFinite(where + ".orientation", state[b].orientation.coeffs());
    RequireFinite(where + ".linear_velocity", state[b].linear_velocity);
    RequireFinite(where + ".angular_velocity", state[b].angular_velocity);
    if (!(state[b].orientation.coeffs().squaredNorm() > 0.0)) {
      throw std::invalid_argument(where + ".orientation must be a non-zero quaternion");
    }
  }
}

double MechanicalEnergy(const Scene& scene, const std::vector<BodyState>& state) {
  double energy = 0.0;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const RigidBody& body = scene.bodies[b];
    const BodyState& s = state[b];
    // ½ m|v_S|² + ½ ωᵀΘω - m g·r_S
    energy += 0.5 * body.mass * s.linear_velocity.squaredNorm() +
              0.5 * s.angular_velocity.dot(body.inertia * s.angular_velocity) -
              body.mass * scene.gravity.dot(s.position);
  }
  return energy;
}

double Inclination(const BodyState& state) {
  // e3 in the world frame is the third column of A(p); atan2 stays accurate near 0 and π
  const Eigen::Vector3d e3 = state.orientation.normalized() * Eigen::Vector3d::UnitZ();
  return std::atan2(std::hypot(e3.x(), e3.y()), e3.z());
}

Eigen::Isometry3d BodyPose(const BodyState& state) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = state.orientation.normalized().toRotationMatrix();
  pose.translation() = state.position;
  return pose;
}

}  // namespace nonsmooth_sim
