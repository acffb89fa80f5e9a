// Bodies that can no longer touch anything (lost_bodies.h): a body without a collider; a body
// below every finite static collider by more than its size; never a body behind a plane (a
// half-space: it is in deep contact, which the gap correction resolves), nor one under a table
// but above the floor, nor at the boundary, nor without gravity.
#include <gtest/gtest.h>

#include <cmath>

#include "nonsmooth_sim/core/shape.h"
#include "nonsmooth_sim/world/lost_bodies.h"

namespace nonsmooth_sim::world {
namespace {

constexpr double kRadius = 0.05;  // the ball's sphere, at its centre of mass: its size

Collider Static(const std::string& name, const Shape& shape, const Eigen::Isometry3d& pose) {
  Collider c;
  c.name = name;
  c.body = kWorld;
  c.shape = shape;
  c.pose = pose;
  return c;
}

// One ball (body 0, a sphere of kRadius at S) and `statics`.
Scene BallOver(const std::vector<Collider>& statics) {
  Scene scene;
  scene.bodies.push_back(RigidBody{"ball"});
  Collider shell;
  shell.name = "shell";
  shell.body = 0;
  shell.shape = Shape::Sphere(kRadius);
  scene.colliders = statics;
  scene.colliders.push_back(shell);
  scene.initial_state.resize(1);
  return scene;
}

std::vector<BodyState> At(const Eigen::Vector3d& position) {
  std::vector<BodyState> state(1);
  state[0].position = position;
  return state;
}

bool Lost(const Scene& scene, const Eigen::Vector3d& position) {
  const std::vector<LostBody> lost = FindLostBodies(scene, At(position));
  EXPECT_LE(lost.size(), 1u);
  if (lost.empty()) return false;
  EXPECT_EQ(lost[0].body, 0);
  EXPECT_EQ(lost[0].why, LostBody::Why::kBelowEveryStaticCollider);
  return true;
}

const Eigen::Isometry3d kIdentity = Eigen::Isometry3d::Identity();

TEST(LostBodies, APlaneLosesNoBodyWithAColliderHoweverDeep) {
  // behind the ground the ball is in contact with it (a half-space), however deep
  const Scene scene = BallOver({Static("ground", Shape::Plane(), kIdentity)});
  EXPECT_FALSE(Lost(scene, {0.0, 0.0, 0.3}));
  EXPECT_FALSE(Lost(scene, {5.0, -3.0, -100.0}));
  // a finite ledge beside it changes nothing
  const Shape ledge = Shape::Box(Eigen::Vector3d(0.5, 0.5, 0.05));
  const Eigen::Isometry3d at(Eigen::Translation3d(0.0, 0.0, 1.0));
  EXPECT_FALSE(Lost(BallOver({Static("ledge", ledge, at), Static("ground", Shape::Plane(),
                                                                   kIdentity)}),
                    {0.0, 0.0, -100.0}));
}

TEST(LostBodies, AFiniteStaticColliderIsPassedBelowItsLowestPointByMoreThanTheSize) {
  // a table top at z = 1 (half extents 0.5, 0.5, 0.05): lowest point 1 - its bounding radius
  const Shape top = Shape::Box(Eigen::Vector3d(0.5, 0.5, 0.05));
  const Eigen::Isometry3d at(Eigen::Translation3d(0.0, 0.0, 1.0));
  const Scene table = BallOver({Static("top", top, at)});
  const double lowest = 1.0 - BoundingRadius(top);
  EXPECT_FALSE(Lost(table, {0.0, 0.0, 1.5}));
  EXPECT_FALSE(Lost(table, {0.0, 0.0, lowest - 0.9 * kRadius}));
  EXPECT_TRUE(Lost(table, {0.0, 0.0, lowest - 1.1 * kRadius}));
  // with a floor box too, a ball under the table is lost only below the floor
  const Shape slab = Shape::Box(Eigen::Vector3d(0.5, 0.5, 0.1));
  const Eigen::Isometry3d floor_at(Eigen::Translation3d(0.0, 0.0, -0.1));
  const Scene room = BallOver({Static("top", top, at), Static("floor", slab, floor_at)});
  const double floor_lowest = -0.1 - BoundingRadius(slab);
  EXPECT_FALSE(Lost(room, {0.0, 0.0, 0.1}));
  EXPECT_FALSE(Lost(room, {0.0, 0.0, floor_lowest - 0.9 * kRadius}));
  EXPECT_TRUE(Lost(room, {0.0, 0.0, floor_lowest - 1.1 * kRadius}));
  // without gravity there is no "below" a finite collider
  Scene weightless = table;
  weightless.gravity.setZero();
  EXPECT_FALSE(Lost(weightless, {0.0, 0.0, -100.0}));
}

TEST(LostBodies, ABodyWithoutAColliderIsLostWithOrWithoutStaticColliders) {
  Scene scene = BallOver({});
  scene.bodies.push_back(RigidBody{"bare"});
  std::vector<BodyState> state(2);
  state[0].position.z() = -1e6;  // no static collider: the ball has nothing to be beyond
  const std::vector<LostBody> lost = FindLostBodies(scene, state);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].body, 1);
  EXPECT_EQ(lost[0].why, LostBody::Why::kNoCollider);
  EXPECT_EQ(DescribeLostBody(lost[0]), "has no collision: it never touches anything");
  // below a finite static collider by far: the ball too
  scene.colliders.push_back(
      Static("ledge", Shape::Box(Eigen::Vector3d(0.5, 0.5, 0.05)), kIdentity));
  EXPECT_EQ(FindLostBodies(scene, state).size(), 2u);
  EXPECT_EQ(DescribeLostBody(FindLostBodies(scene, state)[0]),
            "is more than its size (0.05 m) below every static collider: fallen off the world, "
            "it touches nothing again");
}

}  // namespace
}  // namespace nonsmooth_sim::world
