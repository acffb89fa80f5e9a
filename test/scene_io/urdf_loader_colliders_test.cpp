// URDF -> Scene, the colliders: each shape tag gives its core shape at the collision's pose
// relative to the centre of mass; links fixed to the massless root are world colliders at their
// world pose; Gazebo's friction tags map onto the contact law; names; pairs without a collide
// function in the options' collision table are reported.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace urdf_test;  // NOLINT

// --- shapes --------------------------------------------------------------------------------------

TEST(UrdfLoader, EachShapeTagGivesItsCoreShapeAtTheCollisionPoseRelativeToTheCentreOfMass) {
  const Eigen::Vector3d com(0.01, 0.02, 0.03);
  const std::string xml = Robot(
      "<inertial><origin xyz=\"0.01 0.02 0.03\"/><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>"
      "<collision name=\"s\"><origin xyz=\"0.1 0 0\"/>"
      "<geometry><sphere radius=\"0.1\"/></geometry></collision>"
      "<collision name=\"cyl\"><origin xyz=\"0 0.1 0\" rpy=\"1.5707963267948966 0 0\"/>"
      "<geometry><cylinder radius=\"0.05\" length=\"0.2\"/></geometry></collision>"
      "<collision name=\"slab\"><origin xyz=\"0 0 0.1\" rpy=\"0 0 0.3\"/>"
      "<geometry><box size=\"0.2 0.4 0.6\"/></geometry></collision>"
      "<collision name=\"shell\"><origin xyz=\"0.05 0 0\" rpy=\"0.1 0.2 0.3\"/>"
      "<geometry><sphere radius=\"0.2\"/></geometry></collision>"
      "<collision name=\"pill\"><origin xyz=\"0 0 -0.1\" rpy=\"0 1.5707963267948966 0\"/>"
      "<geometry><cylinder radius=\"0.01\" length=\"0.07\"/></geometry></collision>",
      "<nonsmooth_sim reference=\"b\">"
      "<collision name=\"shell\"><ellipsoid semi_axes=\"0.2 0.03 0.02\"/></collision>"
      "<collision name=\"pill\"><capsule radius=\"0.01\" length=\"0.05\"/></collision>"
      "</nonsmooth_sim>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  const Scene& scene = urdf.scene;
  ASSERT_EQ(scene.colliders.size(), 6u);  // five shapes and the ground
  const auto expect = [&](int i, const std::string& name, const Shape& shape,
                          const Eigen::Vector3d& xyz, const Eigen::Matrix3d& rotation) {
    const Collider& c = scene.colliders[i];
    EXPECT_EQ(c.name, name);
    EXPECT_EQ(c.body, 0) << name;
    ExpectSameShape(c.shape, shape, name);
    EXPECT_LT((c.pose.translation() - (xyz - com)).norm(), 1e-17) << name;
    EXPECT_LT((c.pose.linear() - rotation).norm(), 1e-15) << name;
  };
  expect(0, "s", Shape::Sphere(0.1), {0.1, 0.0, 0.0}, Eigen::Matrix3d::Identity());
  expect(1, "cyl", Shape::Cylinder(0.05, 0.1), {0.0, 0.1, 0.0}, Rpy(kPi / 2, 0.0, 0.0));
  expect(2, "slab", Shape::Box({0.1, 0.2, 0.3}), {0.0, 0.0, 0.1}, Rpy(0.0, 0.0, 0.3));
  expect(3, "shell", Shape::Ellipsoid({0.2, 0.03, 0.02}), {0.05, 0.0, 0.0}, Rpy(0.1, 0.2, 0.3));
  expect(4, "pill", Shape::Capsule(0.01, 0.025), {0.0, 0.0, -0.1}, Rpy(0.0, kPi / 2, 0.0));
  // the cylinder's axis (shape z) lies along the link's -y: rpy (π/2, 0, 0) turns z to -y
  EXPECT_LT((scene.colliders[1].pose.linear() * Eigen::Vector3d::UnitZ() +
             Eigen::Vector3d::UnitY())
                .norm(),
            1e-15);
  EXPECT_TRUE(urdf.warnings.empty());
}

TEST(UrdfLoader, TableAndWallFixedToTheWorldAreWorldCollidersAtTheirWorldPose) {
  // world -fixed (1, 0, 0.4), yaw 90°-> table -fixed (0.5, 0, 0)-> wall; a ball floats above
  const std::string xml = World(
      "",
      "<link name=\"table\"><collision name=\"table_top\"><origin xyz=\"0.1 0 0.375\"/>"
      "<geometry><box size=\"1 0.5 0.05\"/></geometry></collision></link>"
      "<link name=\"wall\"><collision name=\"wall\"><origin xyz=\"0 0 0.2\"/>"
      "<geometry><box size=\"0.02 1 0.4\"/></geometry></collision></link>"
      "<joint name=\"world_table\" type=\"fixed\"><parent link=\"world\"/><child link=\"table\"/>"
      "<origin xyz=\"1 0 0.4\" rpy=\"0 0 1.5707963267948966\"/></joint>"
      "<joint name=\"table_wall\" type=\"fixed\"><parent link=\"table\"/><child link=\"wall\"/>"
      "<origin xyz=\"0.5 0 0\"/></joint>" +
          FloatingBall("ball", "1 0 1", "ball") +
          "<gazebo reference=\"table\"><collision><surface><friction><ode><mu>0.6</mu></ode>"
          "</friction></surface></collision></gazebo>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  ASSERT_EQ(urdf.scene.colliders.size(), 4u);  // table_top, wall, ball, ground
  const Collider& top = urdf.scene.colliders[0];
  const Collider& wall = urdf.scene.colliders[1];
  EXPECT_EQ(top.name, "table_top");
  EXPECT_EQ(top.body, kWorld);
  ExpectSameShape(top.shape, Shape::Box({0.5, 0.25, 0.025}), "table_top");
  // by hand: Rz(90°) (0.1, 0, 0.375) + (1, 0, 0.4) = (1, 0.1, 0.775)
  EXPECT_LT((top.pose.translation() - Eigen::Vector3d(1.0, 0.1, 0.775)).norm(), 1e-15);
  EXPECT_LT((top.pose.linear() - Rpy(0.0, 0.0, kPi / 2)).norm(), 1e-15);
  EXPECT_EQ(top.law.mu, 0.6);
  // wall frame at Rz(90°) (0.5, 0, 0) + (1, 0, 0.4) = (1, 0.5, 0.4), the box 0.2 above it
  EXPECT_EQ(wall.name, "wall");
  EXPECT_EQ(wall.body, kWorld);
  EXPECT_LT((wall.pose.translation() - Eigen::Vector3d(1.0, 0.5, 0.6)).norm(), 1e-15);
  EXPECT_LT((wall.pose.linear() - Rpy(0.0, 0.0, kPi / 2)).norm(), 1e-15);
  EXPECT_EQ(wall.law.mu, 1.0);  // SDF default
  EXPECT_EQ(urdf.scene.colliders[2].body, 0);
  EXPECT_EQ(urdf.scene.colliders[3].name, "ground");
  EXPECT_EQ(urdf.scene.initial_state[0].position, Eigen::Vector3d(1.0, 0.0, 1.0));
}

TEST(UrdfLoader, InclinedPlaneIsAPlaneColliderWhoseNormalIsTheRotatedZ) {
  const std::string xml = World(
      "<collision name=\"slope\"><origin xyz=\"0 0 0.1\" rpy=\"0.2 0 0\"/>"
      "<geometry><box size=\"2 2 0.001\"/></geometry></collision>",
      FloatingBall("ball", "0 0 1", "ball") +
          "<nonsmooth_sim reference=\"world\"><collision name=\"slope\"><plane/></collision>"
          "</nonsmooth_sim>");
  UrdfSceneOptions options;
  options.ground = false;
  const UrdfScene urdf = SceneFromUrdf(xml, options);
  ASSERT_EQ(urdf.scene.colliders.size(), 2u);  // slope, ball: no ground
  const Collider& slope = urdf.scene.colliders[0];
  EXPECT_EQ(slope.name, "slope");
  EXPECT_EQ(slope.body, kWorld);
  EXPECT_EQ(slope.shape.type, ShapeType::kPlane);
  // normal Rx(0.2) ẑ = (0, −sin 0.2, cos 0.2), through (0, 0, 0.1)
  EXPECT_LT((slope.pose.linear() * Eigen::Vector3d::UnitZ() -
             Eigen::Vector3d(0.0, -std::sin(0.2), std::cos(0.2)))
                .norm(),
            1e-16);
  EXPECT_EQ(slope.pose.translation(), Eigen::Vector3d(0.0, 0.0, 0.1));
  EXPECT_EQ(urdf.scene.colliders[1].name, "ball");
}

TEST(UrdfLoader, GroundIsTheCoresGroundPlaneAndComesLast) {
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall));
  ASSERT_EQ(urdf.scene.colliders.size(), 2u);
  const Collider& ground = urdf.scene.colliders.back();
  const Collider core = GroundPlane();
  EXPECT_EQ(ground.name, core.name);
  EXPECT_EQ(ground.body, kWorld);
  EXPECT_EQ(ground.pose.matrix(), core.pose.matrix());
  EXPECT_EQ(ground.shape.type, ShapeType::kPlane);
  EXPECT_EQ(ground.law.mu, core.law.mu);
  EXPECT_EQ(ground.law.rbar, core.law.rbar);
  EXPECT_EQ(ground.law.restitution, core.law.restitution);
}

// --- contact laws --------------------------------------------------------------------------------

TEST(UrdfLoader, GazeboFrictionTagsSetTheContactLaw) {
  const std::string surface =
      "<gazebo reference=\"b\"><collision><surface><friction>"
      "<ode><mu>0.5</mu><mu2>0.5</mu2></ode>"
      "<torsional><coefficient>0.25</coefficient><patch_radius>1e-3</patch_radius></torsional>"
      "</friction></surface></collision></gazebo>"
      "<nonsmooth_sim reference=\"b\"><restitution>0.4</restitution>"
      "<friction_set>exact</friction_set></nonsmooth_sim>";
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall, surface));
  const ContactLaw& law = urdf.scene.colliders[0].law;
  EXPECT_EQ(law.mu, 0.5);
  // Gazebo's drilling bound μ_τ (3πR/16) λ_N = R̄ μ λ_N  ⇒  R̄ = 3πR/16 · μ_τ/μ
  EXPECT_NEAR(law.rbar, 3.0 * kPi * 1e-3 / 16.0 * 0.25 / 0.5, 1e-18);
  EXPECT_EQ(law.restitution, 0.4);
  EXPECT_EQ(law.friction_set, FrictionSet::kExact);  // the link's tag beats the option's default
  EXPECT_TRUE(urdf.warnings.empty());

  // μ and R from the options replace both tags: R̄ = 3πR/16 with the one μ
  UrdfSceneOptions options;
  options.mu = 0.2;
  options.contact_radius = 2e-3;
  options.friction_set = FrictionSet::kCoulomb;
  const UrdfScene overridden = SceneFromUrdf(Robot(kUnitInertial + kBall, surface), options);
  EXPECT_EQ(overridden.scene.colliders[0].law.mu, 0.2);
  EXPECT_NEAR(overridden.scene.colliders[0].law.rbar, 3.0 * kPi * 2e-3 / 16.0, 1e-18);
  EXPECT_EQ(overridden.scene.colliders[0].law.friction_set, FrictionSet::kExact);
}

TEST(UrdfLoader, RollingResistanceFromItsTagsAndTheOption) {
  const std::string bullet =
      "<gazebo reference=\"b\"><collision><surface><friction><bullet>"
      "<rolling_friction>2e-4</rolling_friction></bullet></friction></surface></collision>"
      "</gazebo>";
  const std::string own =
      "<nonsmooth_sim reference=\"b\"><rolling_resistance>5e-5</rolling_resistance>"
      "</nonsmooth_sim>";
  // Bullet's rolling friction of a <gazebo> block (or its direct child), a length
  EXPECT_EQ(SceneFromUrdf(Robot(kUnitInertial + kBall, bullet)).scene.colliders[0]
                .law.rolling_resistance,
            2e-4f);
  EXPECT_EQ(SceneFromUrdf(Robot(kUnitInertial + kBall,
                                "<gazebo reference=\"b\"><rolling_friction>3e-4"
                                "</rolling_friction></gazebo>"))
                .scene.colliders[0]
                .law.rolling_resistance,
            3e-4f);
  // the <nonsmooth_sim> tag wins over <gazebo>'s, the option over both
  const std::string both = Robot(kUnitInertial + kBall, bullet + own);
  EXPECT_EQ(SceneFromUrdf(both).scene.colliders[0].law.rolling_resistance, 5e-5f);
  UrdfSceneOptions options;
  options.rolling_resistance = 1e-3;
  EXPECT_EQ(SceneFromUrdf(both, options).scene.colliders[0].law.rolling_resistance, 1e-3f);
  // none given: none; the ground stays neutral (the body's decides)
  const UrdfScene plain = SceneFromUrdf(Robot(kUnitInertial + kBall));
  EXPECT_EQ(plain.scene.colliders[0].law.rolling_resistance, 0.0f);
  EXPECT_EQ(plain.scene.colliders.back().law.rolling_resistance, GroundLaw().rolling_resistance);
}

TEST(UrdfLoader, WithoutTagsSdfDefaultsAndTheOptionsFrictionSetApply) {
  UrdfSceneOptions options;
  options.friction_set = FrictionSet::kEllipsoid;
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall), options);
  const ContactLaw& law = urdf.scene.colliders[0].law;
  EXPECT_EQ(law.mu, 1.0);    // SDF <mu> default
  EXPECT_EQ(law.rbar, 0.0);  // SDF <patch_radius> default 0: no drilling component
  EXPECT_EQ(law.restitution, 0.0);
  EXPECT_EQ(law.friction_set, FrictionSet::kEllipsoid);
}

TEST(UrdfLoader, EachColliderTakesTheLawOfItsOwnLink) {
  // a body b with a fixed link f: f's collisions keep f's tags
  const std::string xml =
      "<robot name=\"r\"><link name=\"b\">" + kUnitInertial + kBall + "</link>"
      "<link name=\"f\"><collision name=\"tip\"><geometry><sphere radius=\"0.01\"/></geometry>"
      "</collision></link>"
      "<joint name=\"bf\" type=\"fixed\"><parent link=\"b\"/><child link=\"f\"/></joint>"
      "<gazebo reference=\"f\"><collision><surface><friction><ode><mu>0.1</mu></ode></friction>"
      "</surface></collision></gazebo>"
      "<nonsmooth_sim reference=\"f\"><restitution>0.5</restitution></nonsmooth_sim></robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  EXPECT_EQ(urdf.scene.colliders[0].law.mu, 1.0);
  EXPECT_EQ(urdf.scene.colliders[1].name, "tip");
  EXPECT_EQ(urdf.scene.colliders[1].law.mu, 0.1);
  EXPECT_EQ(urdf.scene.colliders[1].law.restitution, 0.5);
}

TEST(UrdfLoader, AnisotropicFrictionAndUnknownGazeboReferencesAreReported) {
  const std::string surface =
      "<gazebo reference=\"b\"><collision><surface><friction>"
      "<ode><mu>0.5</mu><mu2>0.7</mu2></ode></friction></surface></collision></gazebo>"
      "<gazebo reference=\"nowhere\"><material>Gazebo/Red</material></gazebo>";
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall, surface));
  EXPECT_TRUE(HasWarning(urdf, {"anisotropic"}));
  EXPECT_TRUE(HasWarning(urdf, {"gazebo reference=\"nowhere\"", "ignored"}));
  EXPECT_EQ(urdf.scene.colliders[0].law.mu, 0.5);
}

// --- names ---------------------------------------------------------------------------------------

TEST(UrdfLoader, UnnamedCollisionsAreNamedAfterTheirLinkAndPosition) {
  const UrdfScene urdf = SceneFromUrdf(Robot(
      kUnitInertial + "<collision><geometry><sphere radius=\"0.1\"/></geometry></collision>" +
      kBall + "<collision><geometry><sphere radius=\"0.2\"/></geometry></collision>"));
  ASSERT_EQ(urdf.scene.colliders.size(), 4u);
  EXPECT_EQ(urdf.scene.colliders[0].name, "b_collision1");
  EXPECT_EQ(urdf.scene.colliders[1].name, "ball");
  EXPECT_EQ(urdf.scene.colliders[2].name, "b_collision3");
}

TEST(UrdfLoader, ANameUsedTwiceIsAnErrorNamingBothLinks) {
  // on one link
  ExpectContains(LoadError(Robot(kUnitInertial + kBall + kBall)),
                 {"link \"b\" > collision \"ball\"", "also used by link \"b\""});
  // on two bodies
  const std::string two = World("", FloatingBall("one", "0 0 1", "ball") +
                                        FloatingBall("two", "1 0 1", "ball"));
  ExpectContains(LoadError(two), {"link \"two\" > collision \"ball\"", "also used by link \"one\"",
                                  "rename one"});
}

TEST(UrdfLoader, GroundIsAReservedNameUnlessTheGroundIsOff) {
  const std::string xml = Robot(
      kUnitInertial + "<collision name=\"ground\"><geometry><sphere radius=\"0.1\"/></geometry>"
                      "</collision>");
  ExpectContains(LoadError(xml), {"collision \"ground\"", "reserved for the ground plane"});
  UrdfSceneOptions options;
  options.ground = false;
  const UrdfScene urdf = SceneFromUrdf(xml, options);
  ASSERT_EQ(urdf.scene.colliders.size(), 1u);
  EXPECT_EQ(urdf.scene.colliders[0].shape.type, ShapeType::kSphere);
}

// --- collide functions ---------------------------------------------------------------------------

TEST(UrdfLoader, PairsWithoutACollideFunctionAreReported) {
  // a ball on a world box: reported with a table without the sphere-box pair, not with the
  // defaults; the scene carries the options' table
  const std::string xml = World(
      "<collision name=\"block\"><geometry><box size=\"1 1 1\"/></geometry></collision>",
      FloatingBall("ball", "0 0 2", "ball"));
  UrdfSceneOptions without_pair;
  without_pair.collision_table.Register(ShapeType::kSphere, ShapeType::kBox, nullptr);
  const UrdfScene missing = SceneFromUrdf(xml, without_pair);
  EXPECT_TRUE(HasWarning(missing, {"no collide function for sphere-box pairs", "\"ball\"",
                                   "\"block\""}));
  EXPECT_EQ(missing.scene.collision_table.Find(ShapeType::kSphere, ShapeType::kBox), nullptr);
  const UrdfScene with_pair = SceneFromUrdf(xml);
  EXPECT_FALSE(HasWarning(with_pair, {"no collide function"}));
  EXPECT_NE(with_pair.scene.collision_table.Find(ShapeType::kSphere, ShapeType::kBox), nullptr);
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
