// Initial conditions: the Tippe-Top start is the core's; a general body is tilted about world x,
// spun about its e3 and rests with its lowest sphere on the ground; overrides replace parts;
// NaN, Inf and out-of-range values are rejected with the field's name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/initial_conditions.h"

namespace nonsmooth_sim::world {

using scene_io::SceneFromUrdf;
using scene_io::UrdfScene;
namespace {

// a body with two spheres off its axis: not a Tippe-Top
UrdfScene Dumbbell() {
  return SceneFromUrdf(
      "<robot name=\"r\"><link name=\"b\"><inertial><mass value=\"1\"/>"
      "<inertia ixx=\"0.02\" ixy=\"0\" ixz=\"0\" iyy=\"0.03\" iyz=\"0\" izz=\"0.04\"/></inertial>"
      "<collision name=\"s1\"><origin xyz=\"0.1 0 0.05\"/>"
      "<geometry><sphere radius=\"0.04\"/></geometry></collision>"
      "<collision name=\"s2\"><origin xyz=\"-0.1 0 0.02\"/>"
      "<geometry><sphere radius=\"0.03\"/></geometry></collision></link></robot>");
}

// lowest point of all sphere colliders of body 0 [m]
double LowestPoint(const Scene& scene, const BodyState& s) {
  double lowest = std::numeric_limits<double>::infinity();
  int spheres = 0;
  for (const Collider& c : scene.colliders) {
    if (c.body != 0) continue;
    EXPECT_EQ(c.shape.type, ShapeType::kSphere) << c.name;
    ++spheres;
    lowest = std::min(lowest,
                      (s.position + s.orientation * c.pose.translation()).z() - c.shape.radius);
  }
  EXPECT_EQ(spheres, 2);  // s1 and s2 of the dumbbell
  return lowest;
}

std::string Message(const InitialConditions& initial) {
  try {
    ValidateInitialConditions(initial);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(InitialConditions, TippeTopStartIsTheCoresForAnyInclinationAndSpin) {
  const UrdfScene urdf = SceneFromUrdf(
      "<robot name=\"t\"><link name=\"tippe_top\"><inertial><mass value=\"6e-3\"/>"
      "<inertia ixx=\"8e-7\" ixy=\"0\" ixz=\"0\" iyy=\"8e-7\" iyz=\"0\" izz=\"7e-7\"/>"
      "</inertial>"
      "<collision name=\"big_sphere\"><origin xyz=\"0 0 0.003\"/>"
      "<geometry><sphere radius=\"0.015\"/></geometry></collision>"
      "<collision name=\"peg_sphere\"><origin xyz=\"0 0 0.016\"/>"
      "<geometry><sphere radius=\"0.005\"/></geometry></collision></link></robot>");
  ASSERT_TRUE(urdf.tippe_top[0].has_value());
  for (const double theta : {0.0, 0.1, 1.0, 3.0}) {
    InitialConditions initial;
    initial.inclination = theta;
    initial.spin = 50.0;
    const BodyState s = InitialState(urdf, 0, initial)[0];
    const BodyState t = TippeTopInitialState(TippeTopParameters{}, {theta, 50.0});
    EXPECT_EQ(s.position, t.position) << theta;
    EXPECT_EQ(s.orientation.coeffs(), t.orientation.coeffs()) << theta;
    EXPECT_EQ(s.angular_velocity, t.angular_velocity) << theta;
    EXPECT_EQ(s.linear_velocity, t.linear_velocity) << theta;
  }
}

TEST(InitialConditions, GeneralBodyIsTiltedSpunAndRestsOnTheGround) {
  const UrdfScene urdf = Dumbbell();
  ASSERT_FALSE(urdf.tippe_top[0].has_value());
  InitialConditions initial;
  initial.inclination = 0.7;
  initial.spin = 12.0;
  const BodyState s = InitialState(urdf, 0, initial)[0];
  // e3 tilted about world x: e3_world = (0, -sin θ, cos θ)
  EXPECT_LT((s.orientation * Eigen::Vector3d::UnitZ() -
             Eigen::Vector3d(0.0, -std::sin(0.7), std::cos(0.7)))
                .norm(),
            1e-15);
  EXPECT_EQ(s.angular_velocity, Eigen::Vector3d(0.0, 0.0, 12.0));
  EXPECT_EQ(s.linear_velocity, Eigen::Vector3d::Zero());
  EXPECT_NEAR(LowestPoint(urdf.scene, s), 0.0, 1e-15);
}

TEST(InitialConditions, OverridesReplaceTheirPart) {
  const UrdfScene urdf = Dumbbell();
  InitialConditions initial;
  initial.orientation = Eigen::Quaterniond(2.0, 0.0, 2.0, 0.0);  // not normalised: 90° about y
  const BodyState turned = InitialState(urdf, 0, initial)[0];
  EXPECT_NEAR(turned.orientation.norm(), 1.0, 1e-15);
  EXPECT_NEAR(LowestPoint(urdf.scene, turned), 0.0, 1e-15);  // lowered onto the ground again

  initial.position = Eigen::Vector3d(1.0, 2.0, 3.0);
  initial.linear_velocity = Eigen::Vector3d(0.1, 0.2, 0.3);
  initial.angular_velocity = Eigen::Vector3d(4.0, 5.0, 6.0);
  const BodyState s = InitialState(urdf, 0, initial)[0];
  EXPECT_EQ(s.position, *initial.position);
  EXPECT_EQ(s.linear_velocity, *initial.linear_velocity);
  EXPECT_EQ(s.angular_velocity, *initial.angular_velocity);
  EXPECT_EQ(s.orientation.coeffs(), turned.orientation.coeffs());
}

TEST(InitialConditions, MergeTakesEachSetFieldOfTheOverrides) {
  InitialConditions defaults;
  defaults.inclination = 0.1;
  defaults.spin = 180.0;
  defaults.position = Eigen::Vector3d(1.0, 1.0, 1.0);
  InitialConditions overrides;
  overrides.spin = 5.0;
  overrides.linear_velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
  const InitialConditions m = Merge(defaults, overrides);
  EXPECT_EQ(*m.inclination, 0.1);
  EXPECT_EQ(*m.spin, 5.0);
  EXPECT_EQ(*m.position, Eigen::Vector3d(1.0, 1.0, 1.0));
  EXPECT_EQ(*m.linear_velocity, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_FALSE(m.orientation.has_value());
}

TEST(InitialConditions, NonFiniteAndOutOfRangeValuesAreRejectedByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  InitialConditions ic;
  ic.inclination = nan;
  EXPECT_NE(Message(ic).find("inclination"), std::string::npos);
  ic.inclination = 3.2;
  EXPECT_NE(Message(ic).find("[0, pi]"), std::string::npos);
  ic.inclination = -0.1;
  EXPECT_NE(Message(ic).find("[0, pi]"), std::string::npos);
  ic = {};
  ic.spin = inf;
  EXPECT_NE(Message(ic).find("spin"), std::string::npos);
  ic = {};
  ic.orientation = Eigen::Quaterniond(0.0, 0.0, 0.0, 0.0);
  EXPECT_NE(Message(ic).find("non-zero"), std::string::npos);
  // finite components whose |q|² overflows: they normalise to (0, 0, 0, 0) or NaN
  ic.orientation = Eigen::Quaterniond(1.0, 1e300, 0.0, 0.0);
  EXPECT_NE(Message(ic).find("|q|^2 finite"), std::string::npos);
  ic = {};
  ic.position = Eigen::Vector3d(0.0, nan, 0.0);
  EXPECT_NE(Message(ic).find("position"), std::string::npos);
  ic = {};
  ic.angular_velocity = Eigen::Vector3d(0.0, 0.0, -inf);
  EXPECT_NE(Message(ic).find("angular_velocity"), std::string::npos);
  ic = {};
  ic.inclination = 3.14159;
  EXPECT_EQ(Message(ic), "");
  // InitialState validates too
  ic.spin = nan;
  EXPECT_THROW(InitialState(Dumbbell(), 0, ic), std::invalid_argument);
}

}  // namespace
}  // namespace nonsmooth_sim::world
