// The position projection stage on its own (core/step/position_projection.h), on constructed
// penetrations: the closed contacts are built here from the collision table at the end state
// (as the contact pipeline would have closed them), and CorrectGaps moves the bodies. Closed
// forms of the lift (one body on a plane, the highest of several points, two bodies sharing it by
// mass), the levelling of a body on several points of a plane (a level box stays level, a
// tilted box ends with every point at the slop), and no lift opens a contact that carried.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/contact/contact_key.h"
#include "nonsmooth_sim/core/step/position_projection.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

using test::ColliderWorldPose;

RigidBody Body(double mass) {
  RigidBody body;
  body.mass = mass;
  body.inertia = Eigen::Matrix3d::Identity() * (0.004 * mass);
  return body;
}

Collider OnBody(int body, const Shape& shape,
                const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  Collider c;
  c.name = "c" + std::to_string(body) + "_" + std::to_string(offset.x());
  c.body = body;
  c.pose.translation() = offset;
  c.shape = shape;
  return c;
}

// A model, its step data and an end state q_E; Close() builds the closed contacts at q_E.
struct Projection {
  Model model;
  StepData data;
  std::vector<BodyState> state;

  explicit Projection(const Scene& scene) {
    model.scene = scene;
    model.BuildCaches();
    data.Resize(model);
    state = scene.initial_state;
  }
  // every pair of colliders on different bodies (or a body and a static one) with g ≤ 0 at
  // `state`, ordered by pair, A the static collider if there is one (the pipeline's conventions)
  void Close() {
    data.closed_count = 0;
    const std::vector<Collider>& colliders = model.scene.colliders;
    for (int i = 0; i < static_cast<int>(colliders.size()); ++i) {
      for (int j = i + 1; j < static_cast<int>(colliders.size()); ++j) {
        int a = i;
        int b = j;
        if (colliders[static_cast<std::size_t>(b)].body == kWorld) std::swap(a, b);
        const Collider& ca = colliders[static_cast<std::size_t>(a)];
        const Collider& cb = colliders[static_cast<std::size_t>(b)];
        if (cb.body == kWorld || ca.body == cb.body) continue;
        ContactGeometry g[kMaxPairContacts];
        const int count = model.scene.collision_table.Collide(
            ca.shape, ColliderWorldPose(model.scene, state, a), cb.shape,
            ColliderWorldPose(model.scene, state, b), 0.0, g);
        for (int k = 0; k < count; ++k) {
          if (g[k].gap > 0.0) continue;
          if (data.closed_count == data.closed.size()) data.closed.emplace_back();
          ClosedContact& c = data.closed[data.closed_count++];
          c.key = ContactKey(i, j, g[k].feature);
          c.report.collider_a = a;
          c.report.collider_b = b;
          c.report.body_a = ca.body;
          c.report.body_b = cb.body;
          c.report.feature = g[k].feature;
          c.report.gap = g[k].gap;
          c.report.point = g[k].point_b;
          c.report.frame.normal = g[k].normal;
        }
      }
    }
    for (std::size_t b = 0; b < state.size(); ++b) {
      data.body[b].rotation_end = state[b].orientation.toRotationMatrix();
    }
  }
  bool Project(StepStatistics* stats) {
    PositionProjection projection;
    return projection.CorrectGaps(model, &data, &state, stats);
  }
  // the gaps of the pair (first, second) at `state`, by the collision table, by feature
  std::map<int, double> Gaps(int first, int second) const {
    ContactGeometry g[kMaxPairContacts];
    const int count = model.scene.collision_table.Collide(
        model.scene.colliders[static_cast<std::size_t>(first)].shape,
        ColliderWorldPose(model.scene, state, first),
        model.scene.colliders[static_cast<std::size_t>(second)].shape,
        ColliderWorldPose(model.scene, state, second), 1.0, g);
    std::map<int, double> gaps;
    for (int k = 0; k < count; ++k) gaps[g[k].feature] = g[k].gap;
    return gaps;
  }
};

Scene OneBodyOnTheGround(const Collider& collider, const Eigen::Vector3d& position,
                         const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity()) {
  Scene scene;
  scene.bodies = {Body(2.0)};
  scene.colliders = {GroundPlane(), collider};
  BodyState s;
  s.position = position;
  s.orientation = orientation;
  scene.initial_state = {s};
  return scene;
}

TEST(PositionProjection, ASphereOnAPlaneIsLiftedToTheSlop) {
  const double r = 0.1;
  const double depth = 1e-4;
  Projection p(
      OneBodyOnTheGround(OnBody(0, Shape::Sphere(r)), Eigen::Vector3d(0.3, -0.2, r - depth)));
  p.Close();
  ASSERT_EQ(p.data.closed_count, 1u);
  StepStatistics stats;
  EXPECT_TRUE(p.Project(&stats));
  // Δr = (depth - slop) ẑ, closed form; the end gap is -slop
  const double lift = depth - kGapCorrectionSlop;
  EXPECT_NEAR(p.state[0].position.z(), r - depth + lift, 1e-16);
  EXPECT_EQ(p.state[0].position.x(), 0.3);
  EXPECT_EQ(p.state[0].position.y(), -0.2);
  EXPECT_NEAR(p.Gaps(0, 1).begin()->second, -kGapCorrectionSlop, 1e-16);
  EXPECT_NEAR(stats.gap_correction, lift, 1e-16);
  EXPECT_NEAR(stats.gap_correction_energy, 2.0 * 9.81 * lift, 1e-15);  // -m g·Δr
}

TEST(PositionProjection, APenetrationWithinTheSlopIsKept) {
  const double r = 0.1;
  const Eigen::Vector3d start(0.0, 0.0, r - 0.5 * kGapCorrectionSlop);
  Projection p(OneBodyOnTheGround(OnBody(0, Shape::Sphere(r)), start));
  p.Close();
  ASSERT_EQ(p.data.closed_count, 1u);
  StepStatistics stats;
  EXPECT_FALSE(p.Project(&stats));
  EXPECT_EQ(p.state[0].position, start);
  EXPECT_EQ(stats.gap_correction, 0.0);
}

TEST(PositionProjection, TheHighestOfSeveralContactsDecidesAndNoneOpens) {
  // a body on two spheres of one static plane (two pairs, one group): lifted by the shallower
  // depth less the slop, so the shallower stays closed at -slop and the deeper stays deeper
  Scene scene;
  scene.bodies = {Body(1.0)};
  const double r = 0.05;
  scene.colliders = {OnBody(0, Shape::Sphere(r), Eigen::Vector3d(-0.1, 0, 0)),
                     OnBody(0, Shape::Sphere(r), Eigen::Vector3d(0.1, 0, 0)), GroundPlane()};
  const double deep = 3e-4;
  const double shallow = 5e-5;
  // tilted about y so that the left sphere is `deep` and the right one `shallow` in the ground
  const double angle = -std::asin((deep - shallow) / 0.2);
  BodyState s;
  s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
  s.position = Eigen::Vector3d(0, 0, r - 0.5 * (deep + shallow));
  scene.initial_state = {s};
  Projection p(scene);
  p.Close();
  ASSERT_EQ(p.data.closed_count, 2u);
  ASSERT_NEAR(p.Gaps(0, 2).begin()->second, -deep, 1e-15);
  ASSERT_NEAR(p.Gaps(1, 2).begin()->second, -shallow, 1e-15);
  StepStatistics stats;
  EXPECT_TRUE(p.Project(&stats));
  EXPECT_NEAR(p.state[0].position.z() - s.position.z(), shallow - kGapCorrectionSlop, 1e-16);
  EXPECT_EQ(p.state[0].orientation.coeffs(), s.orientation.coeffs());  // a lift turns nothing
  const double left = p.Gaps(0, 2).begin()->second;
  const double right = p.Gaps(1, 2).begin()->second;
  EXPECT_NEAR(right, -kGapCorrectionSlop, 1e-15);
  EXPECT_LE(right, 0.0);  // the carrying contact is not opened
  EXPECT_NEAR(left, -(deep - shallow + kGapCorrectionSlop), 1e-15);
}

TEST(PositionProjection, TwoBodiesShareTheLiftByMassAndKeepTheirCentreOfMass) {
  // sphere B (3 kg) on sphere A (1 kg), along z, `depth` into each other; no ground
  Scene scene;
  scene.bodies = {Body(1.0), Body(3.0)};
  const double r = 0.05;
  const double depth = 2e-4;
  scene.colliders = {OnBody(0, Shape::Sphere(r)), OnBody(1, Shape::Sphere(r))};
  BodyState a;
  a.position = Eigen::Vector3d(0.1, 0.2, 0.3);
  BodyState b = a;
  b.position.z() += 2 * r - depth;
  scene.initial_state = {a, b};
  Projection p(scene);
  p.Close();
  ASSERT_EQ(p.data.closed_count, 1u);
  StepStatistics stats;
  EXPECT_TRUE(p.Project(&stats));
  const double push = depth - kGapCorrectionSlop;
  // B moves m_A/(m_A + m_B) of the push along n = +z, A the rest against it
  EXPECT_NEAR(p.state[1].position.z() - b.position.z(), 0.25 * push, 1e-16);
  EXPECT_NEAR(p.state[0].position.z() - a.position.z(), -0.75 * push, 1e-16);
  const double centre_before = (1.0 * a.position.z() + 3.0 * b.position.z()) / 4.0;
  const double centre_after = (1.0 * p.state[0].position.z() + 3.0 * p.state[1].position.z()) / 4.0;
  EXPECT_NEAR(centre_after, centre_before, 1e-16);
  EXPECT_NEAR(p.Gaps(0, 1).begin()->second, -kGapCorrectionSlop, 1e-15);
  EXPECT_NEAR(stats.gap_correction, 0.75 * push, 1e-16);
}

// A box lying flat `depth` into the ground (one pair, its four face points closed), levelled.
void ExpectALevelBoxStaysLevel(double depth, double max_tilt, double max_error) {
  const Eigen::Vector3d half(0.05, 0.03, 0.02);
  Projection p(
      OneBodyOnTheGround(OnBody(0, Shape::Box(half)), Eigen::Vector3d(0, 0, half.z() - depth)));
  p.Close();
  ASSERT_EQ(p.data.closed_count, 4u);
  const std::map<int, double> before = p.Gaps(0, 1);
  StepStatistics stats;
  EXPECT_TRUE(p.Project(&stats));
  const double tilt = Eigen::AngleAxisd(p.state[0].orientation).angle();
  EXPECT_LE(tilt, max_tilt) << "depth " << depth;
  EXPECT_NEAR(p.state[0].position.z(), half.z() - kGapCorrectionSlop, max_error);
  const std::map<int, double> after = p.Gaps(0, 1);
  for (const auto& [feature, gap] : before) {
    if (gap > 0.0) continue;
    EXPECT_NEAR(after.at(feature), -kGapCorrectionSlop, max_error) << "point " << feature;
    EXPECT_LE(after.at(feature), 0.0) << "point " << feature;  // still carrying
  }
}

TEST(PositionProjection, ALevelBoxStaysLevel) {
  // the projected Gauss-Seidel sweeps (kLevellingSweeps) level the four symmetric points one
  // after the other, so a level box keeps a tilt that the sweeps have not yet removed, its face
  // points at -slop: measured 6.0e-9 rad and 1.1e-10 m at 10 µm deep (a step's drift is far
  // less), 6.6e-8 rad and 1.2e-9 m at 100 µm
  ExpectALevelBoxStaysLevel(1e-5, 1e-8, 2e-10);
  ExpectALevelBoxStaysLevel(1e-4, 1e-7, 2e-9);
}

TEST(PositionProjection, ABuriedLevelBoxIsLiftedOutAndStaysLevel) {
  // 10 m deep, far deeper than its bounding diameter: lifted along the normal until its highest
  // point is at -slop, the rest (its height) levelled: out of the ground and level up to the
  // sweeps' remainder (measured 2.7e-5 rad, S 4.9e-7 m above its place at the slop; without the
  // straight lift the sweeps left a die 10 m deep turned by 0.67 rad)
  const Eigen::Vector3d half(0.05, 0.03, 0.02);
  Projection p(OneBodyOnTheGround(OnBody(0, Shape::Box(half)), Eigen::Vector3d(0, 0, -10.0)));
  p.Close();
  ASSERT_GE(p.data.closed_count, 2u);
  StepStatistics stats;
  EXPECT_TRUE(p.Project(&stats));
  const double tilt = Eigen::AngleAxisd(p.state[0].orientation).angle();
  EXPECT_LE(tilt, 5e-5);
  EXPECT_NEAR(p.state[0].position.z(), half.z() - kGapCorrectionSlop, 1e-6);
}

TEST(PositionProjection, ATiltedBoxIsLevelledOntoItsPointsWithoutOpeningOne) {
  // a box tilted about x: its lower edge's two corners are closed at different depths (a slight
  // turn about y too); the levelling brings both to -slop (within the sweeps' tolerance), opens
  // neither, and turns the box (a lift alone would leave the deeper one deeper)
  const Eigen::Vector3d half(0.05, 0.03, 0.02);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(2e-4, Eigen::Vector3d::UnitY()));
  const Eigen::Matrix3d rotation = q.toRotationMatrix();
  double lowest = 0.0;  // of the corners, relative to S
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1 ? 1 : -1) * half.x(), (k & 2 ? 1 : -1) * half.y(),
                                 (k & 4 ? 1 : -1) * half.z());
    lowest = std::min(lowest, (rotation * corner).z());
  }
  Projection p(OneBodyOnTheGround(OnBody(0, Shape::Box(half)),
                                  Eigen::Vector3d(0, 0, -lowest - 2e-4), q));
  p.Close();
  ASSERT_EQ(p.data.closed_count, 2u);
  const std::map<int, double> before = p.Gaps(0, 1);
  StepStatistics stats;
  EXPECT_TRUE(p.Project(&stats));
  const std::map<int, double> after = p.Gaps(0, 1);
  int closed = 0;
  for (const auto& [feature, gap] : before) {
    if (gap > 0.0) continue;
    ++closed;
    ASSERT_EQ(after.count(feature), 1u) << "corner " << feature;
    // at the slop or above it, up to what the sweeps leave (measured 1.4e-8 m above), and not
    // opened: the lift never opens a carrying contact
    EXPECT_GE(after.at(feature), -kGapCorrectionSlop - 1e-12) << "corner " << feature;
    EXPECT_LE(after.at(feature), -0.9 * kGapCorrectionSlop) << "corner " << feature;
  }
  EXPECT_EQ(closed, 2);
  EXPECT_GT(Eigen::AngleAxisd(p.state[0].orientation * q.conjugate()).angle(), 1e-6);
}

}  // namespace
}  // namespace nonsmooth_sim
