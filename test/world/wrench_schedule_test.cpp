// The wrench schedule: the impulse of a wrench over its duration T is F·T whatever the steps
// (closed form Δv = F T / m for a free body), the torque of a force applied off the centre of
// mass is r × F with the arm turning with the body, and a refused request changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "world_fixtures.h"

namespace nonsmooth_sim::world {
namespace {

using testing::BallUrdf;
using testing::Load;
using testing::WorldSnapshot;

constexpr double kMass = 2.0;  // of BallUrdf [kg]
constexpr double kDt = 1e-3;   // [s]

// The ball in free space: no gravity, no ground.
World FreeBall() {
  WorldConfig config;
  config.simulator.time_step = kDt;
  return World(Load(BallUrdf(), 0.0, /*ground=*/false), config);
}

void Steps(World* w, int n) {
  for (int k = 0; k < n; ++k) {
    w->ApplyScheduledWrenches(kDt);
    w->sim().Step();
  }
}

TEST(WrenchSchedule, ImpulseIsForceTimesDurationForAnyDurationAndStart) {
  // durations and starts that are not whole steps: the parts of the first and last step count
  for (const double duration : {0.1, 0.0105, 0.00037}) {
    for (const double start : {0.0, 0.0042}) {
      World w = FreeBall();
      WrenchRequest push;
      push.body = "ball";
      push.force = Eigen::Vector3d(3.0, -1.5, 0.25);
      push.start = start;
      push.duration = duration;
      ASSERT_TRUE(w.ApplyWrench(push));
      Steps(&w, static_cast<int>(std::ceil((start + duration) / kDt)) + 3);
      const Eigen::Vector3d v = w.sim().state()[0].linear_velocity;
      const Eigen::Vector3d expected = push.force * duration / kMass;  // Δv = F T / m
      EXPECT_LT((v - expected).norm(), 1e-12 * expected.norm())
          << "T = " << duration << " s from " << start << " s: v = " << v.transpose();
      // and it is over: nothing scheduled, the core's wrench cleared
      EXPECT_TRUE(w.wrenches().wrenches().empty());
      EXPECT_TRUE(w.sim().ExternalWrench(0).first.isZero(0.0));
      EXPECT_FALSE(w.wrenches().active());
    }
  }
}

TEST(WrenchSchedule, ForceOffTheCentreGivesTheMomentArmTorque) {
  World w = FreeBall();
  WrenchRequest push;
  push.body = "ball";
  push.force = Eigen::Vector3d(0.0, 2.0, 0.0);
  push.torque = Eigen::Vector3d(0.0, 0.0, 0.5);
  push.point = Eigen::Vector3d(0.05, 0.0, 0.01);  // world frame; S at the origin
  push.duration = -1.0;                           // until cleared
  ASSERT_TRUE(w.ApplyWrench(push));
  w.ApplyScheduledWrenches(kDt);
  const auto [force, torque] = w.sim().ExternalWrench(0);
  EXPECT_EQ(force, push.force);
  const Eigen::Vector3d expected = push.torque + push.point.cross(push.force);  // M + r × F
  EXPECT_LT((torque - expected).norm(), 1e-15) << torque.transpose();

  // the point is fixed in the body: turned by a quarter about z, the arm turns with it
  BodyState s = w.sim().state()[0];
  const Eigen::Quaterniond quarter(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  s.orientation = quarter;
  w.sim().SetState({s});
  w.ApplyScheduledWrenches(kDt);
  const Eigen::Vector3d turned = push.torque + (quarter * push.point).cross(push.force);
  EXPECT_LT((w.sim().ExternalWrench(0).second - turned).norm(), 1e-15);

  EXPECT_TRUE(w.ClearWrenches("ball"));
  EXPECT_TRUE(w.sim().ExternalWrench(0).second.isZero(0.0));
  EXPECT_TRUE(w.wrenches().wrenches().empty());
  EXPECT_FALSE(w.ClearWrenches("no_such_body"));
}

TEST(WrenchSchedule, RefusedRequestsChangeNothing) {
  World w = FreeBall();
  WrenchRequest good;
  good.body = "ball";
  good.force = Eigen::Vector3d(1, 0, 0);
  good.duration = 1.0;
  ASSERT_TRUE(w.ApplyWrench(good));
  Steps(&w, 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  WrenchRequest bad[7];
  for (WrenchRequest& r : bad) r = good;
  bad[0].body = "nobody";
  bad[1].reference_frame = "nowhere";
  bad[2].force = Eigen::Vector3d(nan, 0, 0);
  bad[3].force = Eigen::Vector3d(2e6, 0, 0);  // above WrenchSchedule::kMaxForce
  bad[4].torque = Eigen::Vector3d(0, 0, inf);
  bad[5].point = Eigen::Vector3d(0, 2e3, 0);  // beyond kMaxInitialCoordinate
  bad[6].duration = nan;
  for (const WrenchRequest& r : bad) {
    const WorldSnapshot before(w);
    EXPECT_THROW(w.ApplyWrench(r), std::invalid_argument);
    before.ExpectSame(WorldSnapshot(w), "apply_body_wrench");
  }
  // duration 0: accepted, nothing scheduled
  WrenchRequest nothing = good;
  nothing.duration = 0.0;
  const WorldSnapshot before(w);
  EXPECT_FALSE(w.ApplyWrench(nothing));
  before.ExpectSame(WorldSnapshot(w), "duration 0");
}

TEST(WrenchSchedule, HoldsAtMostTheBoundAndRefusesOneMore) {
  World w = FreeBall();
  WrenchRequest r;
  r.body = "ball";
  r.force = Eigen::Vector3d(1e-3, 0, 0);
  r.duration = 1.0;
  for (std::size_t k = 0; k < WrenchSchedule::kMaxWrenches; ++k) ASSERT_TRUE(w.ApplyWrench(r));
  const WorldSnapshot before(w);
  EXPECT_THROW(w.ApplyWrench(r), std::invalid_argument);
  before.ExpectSame(WorldSnapshot(w), "one wrench beyond the bound");
}

}  // namespace
}  // namespace nonsmooth_sim::world
