// Two Tippe-Tops in one scene move as if each were alone (contacts of different bodies do not
// couple through the fixed ground).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

using test::AddGround;

TEST(MultiBody, TwoTopsInOneSceneMoveAsIfAlone) {
  // two Tippe-Tops with different initial conditions in one scene (bodies 0 and 1, sphere
  // colliders 0-1 on body 0 and 2-3 on body 1, the ground last): contacts of different bodies do
  // not couple through the fixed ground, so each must follow its own single-body run. A tight
  // solver tolerance keeps the stopping rule from mattering; measured max differences 2e-17 m and
  // 6e-14 rad/s.
  SimulatorOptions options;
  options.solver.tolerance_rel = 1e-12;
  options.solver.tolerance_abs = 1e-20;
  options.solver.max_iterations = 100000;
  TippeTopInitialConditions second;
  second.inclination = 0.3;
  second.spin = 150.0;
  const Scene a = MakeTippeTopScene();
  Scene b = MakeTippeTopScene(TippeTopParameters{}, second);
  b.initial_state[0].position.x() = 0.5;
  Scene both = a;
  both.bodies.push_back(b.bodies[0]);
  both.initial_state.push_back(b.initial_state[0]);
  both.colliders.clear();
  for (int body = 0; body < 2; ++body) {
    for (Collider collider : (body == 0 ? a : b).colliders) {
      if (collider.body == kWorld) continue;
      collider.body = body;
      if (body == 1) collider.name += "_1";  // names are unique in a scene
      both.colliders.push_back(collider);
    }
  }
  AddGround(&both);
  ASSERT_EQ(both.colliders.size(), 5u);
  Simulator alone_a(a, options), alone_b(b, options), together(both, options);
  double worst = 0.0;
  int max_closed = 0;
  int max_islands = 0;
  for (int k = 0; k < 3000; ++k) {
    alone_a.Step();
    alone_b.Step();
    const StepStatistics stats = together.Step();
    max_closed = std::max(max_closed, stats.closed_contacts);
    max_islands = std::max(max_islands, stats.islands);
    worst = std::max(worst, (together.state()[0].position - alone_a.state()[0].position).norm());
    worst = std::max(worst, (together.state()[1].position - alone_b.state()[0].position).norm());
    worst = std::max(worst, (together.state()[1].angular_velocity -
                             alone_b.state()[0].angular_velocity).norm() * 1e-3);
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GE(max_closed, 2);
  // the two tops touching at once are two separate contact problems
  EXPECT_EQ(max_islands, 2);
  EXPECT_EQ(together.InContact(2), alone_b.InContact(kBigSphere));
}

}  // namespace
}  // namespace nonsmooth_sim
