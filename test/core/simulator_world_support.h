// Shared by the tests of the world changed between two steps (simulator_world_*_test.cpp,
// simulator_external_wrench_test.cpp): bit-for-bit comparison of states, contact reports and step
// statistics, and worlds of Tippe-Tops built model by model. Fixed initial conditions, no timing.
#ifndef NONSMOOTH_SIM_TEST_CORE_SIMULATOR_WORLD_SUPPORT_H_
#define NONSMOOTH_SIM_TEST_CORE_SIMULATOR_WORLD_SUPPORT_H_

#include <Eigen/Core>
#include <sstream>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "scene_builders.h"

namespace nonsmooth_sim::simulator_world_support {

// --- bit-for-bit comparison

// "" if every coefficient of the two states is equal (==), else the first difference.
inline std::string StateDifference(const BodyState& a, const BodyState& b) {
  std::ostringstream s;
  s.precision(17);
  auto compare = [&s](const char* what, const Eigen::Ref<const Eigen::VectorXd>& x,
                      const Eigen::Ref<const Eigen::VectorXd>& y) {
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (x[i] != y[i] && s.tellp() == 0) {
        s << what << "[" << i << "]: " << x[i] << " != " << y[i];
      }
    }
  };
  compare("position", a.position, b.position);
  compare("orientation", a.orientation.coeffs(), b.orientation.coeffs());
  compare("linear_velocity", a.linear_velocity, b.linear_velocity);
  compare("angular_velocity", a.angular_velocity, b.angular_velocity);
  return s.str();
}

// The contact reports of two simulators, where a may have more than b: `collider_map` /
// `body_map` take b's indices to a's, and a's contacts between colliders b has (in their image)
// must be b's, in order, in every field.
inline std::string ContactsDifference(const Simulator& a, const Simulator& b,
                                      const std::vector<int>& collider_map,
                                      const std::vector<int>& body_map) {
  std::ostringstream s;
  auto in_b = [&collider_map](int collider) {
    return std::find(collider_map.begin(), collider_map.end(), collider) != collider_map.end();
  };
  std::vector<ContactState> of_b;
  for (const ContactState& x : a.contacts()) {
    if (in_b(x.collider_a) && in_b(x.collider_b)) of_b.push_back(x);
  }
  if (of_b.size() != b.contacts().size()) {
    s << of_b.size() << " contacts != " << b.contacts().size();
    return s.str();
  }
  auto body = [&body_map](int x) { return x == kWorld ? kWorld : body_map.at(x); };
  for (std::size_t i = 0; i < of_b.size(); ++i) {
    const ContactState& x = of_b[i];
    const ContactState& y = b.contacts()[i];
    if (x.collider_a != collider_map.at(y.collider_a) ||
        x.collider_b != collider_map.at(y.collider_b) || x.body_a != body(y.body_a) ||
        x.body_b != body(y.body_b) || x.feature != y.feature || x.gap != y.gap ||
        x.percussion != y.percussion || x.frame.tangent1 != y.frame.tangent1 ||
        x.relative_velocity != y.relative_velocity ||
        ContactName(a.scene(), x) != ContactName(b.scene(), y)) {
      s << "contact " << i << " differs (" << ContactName(a.scene(), x) << " vs "
        << ContactName(b.scene(), y) << ")";
      return s.str();
    }
  }
  return "";
}

// The statistics a step reports (its work: iterations show the warm start).
inline std::string StatisticsDifference(const StepStatistics& a, const StepStatistics& b) {
  std::ostringstream s;
  if (a.solver.iterations != b.solver.iterations) {
    s << "iterations " << a.solver.iterations << " != " << b.solver.iterations;
  } else if (a.closed_contacts != b.closed_contacts) {
    s << "closed contacts " << a.closed_contacts << " != " << b.closed_contacts;
  } else if (a.gap_correction != b.gap_correction) {
    s << "gap correction " << a.gap_correction << " != " << b.gap_correction;
  }
  return s.str();
}

// --- scenes

// A Tippe-Top as a model: body "top_<tag>", colliders "<tag>_big", "<tag>_peg" (no ground), and
// its start state shifted by `x` along the world x axis.
struct Model {
  Scene scene;
  BodyState state;
};
inline Model TippeTopModel(const std::string& tag, double inclination, double spin, double x,
                           FrictionSet set = FrictionSet::kSphere) {
  TippeTopParameters parameters;
  parameters.friction_set = set;
  TippeTopInitialConditions initial;
  initial.inclination = inclination;
  initial.spin = spin;
  const Scene top = MakeTippeTopScene(parameters, initial);
  Model model;
  model.scene.bodies = top.bodies;
  model.scene.bodies[0].name = "top_" + tag;
  for (Collider collider : top.colliders) {
    if (collider.body == kWorld) continue;
    collider.name = tag + (collider.name == "big_sphere" ? "_big" : "_peg");
    model.scene.colliders.push_back(collider);
  }
  model.state = top.initial_state[0];
  model.state.position.x() += x;
  model.scene.initial_state = {model.state};
  return model;
}

// The models' bodies and colliders in order, the ground first or last.
inline Scene World(const std::vector<const Model*>& models, bool ground_first) {
  Scene scene;
  if (ground_first) test::AddGround(&scene);
  for (const Model* model : models) {
    const int offset = static_cast<int>(scene.bodies.size());
    for (const RigidBody& body : model->scene.bodies) scene.bodies.push_back(body);
    for (Collider collider : model->scene.colliders) {
      if (collider.body != kWorld) collider.body += offset;
      scene.colliders.push_back(collider);
    }
    scene.initial_state.push_back(model->state);
  }
  if (!ground_first) test::AddGround(&scene);
  return scene;
}

// Two tops 1 m apart, different enough to tell apart: A tilted 0.1 rad spinning at 180 rad/s at
// the origin (it inverts), B tilted 0.3 rad at 150 rad/s.
inline Model TopA(FrictionSet set = FrictionSet::kSphere) {
  return TippeTopModel("a", 0.1, 180.0, 0.0, set);
}
inline Model TopB(FrictionSet set = FrictionSet::kSphere) {
  return TippeTopModel("b", 0.3, 150.0, 1.0, set);
}

}  // namespace nonsmooth_sim::simulator_world_support

#endif  // NONSMOOTH_SIM_TEST_CORE_SIMULATOR_WORLD_SUPPORT_H_
