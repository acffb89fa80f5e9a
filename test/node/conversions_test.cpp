// Core -> messages: stamps never 0, forces are percussions / Δt in the contact frame, the link
// pose accounts for the centre-of-mass offset, state fields agree with the core's functions.
// ~contacts lists the closed contacts only, named "<first collision>/<second collision>"; a slot's
// wrench is the total contact wrench on its collider in its slot frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/node/conversions.h"

namespace nonsmooth_sim::node {
namespace {

Eigen::Vector3d ToEigen(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
Eigen::Vector3d ToEigen(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

Eigen::Quaterniond ToEigen(const geometry_msgs::Quaternion& q) { return {q.w, q.x, q.y, q.z}; }

// the Tippe-Top upright at rest on its big sphere, after `steps` steps
Simulator RestingTop(int steps) {
  Simulator sim(MakeTippeTopScene({}, {0.0, 0.0}), SimulatorOptions{});
  for (int k = 0; k < steps; ++k) sim.Step();
  return sim;
}

// Whether a contact of collision `name` (on either side) is listed.
bool Lists(const ContactInfoArray& msg, const std::string& name) {
  for (const ContactInfo& c : msg.contacts) {
    if (c.collision == name || c.other_collision == name) return true;
  }
  return false;
}

// Two unit spheres of 1 kg stacked on the ground, on one vertical line: "lower" (body 0) touches
// the ground and "upper" (body 1); at rest after `steps` steps.
constexpr double kStackRadius = 0.05;
constexpr double kStackMass = 1.0;
Simulator SphereStack(int steps) {
  Scene scene;
  for (int b = 0; b < 2; ++b) {
    RigidBody body;
    body.name = b == 0 ? "lower_body" : "upper_body";
    body.mass = kStackMass;
    body.inertia = 0.4 * kStackMass * kStackRadius * kStackRadius * Eigen::Matrix3d::Identity();
    scene.bodies.push_back(body);
    Collider sphere;
    sphere.name = b == 0 ? "lower" : "upper";
    sphere.body = b;
    sphere.shape = Shape::Sphere(kStackRadius);
    sphere.law.mu = 0.5;
    sphere.law.rbar = 1e-3;
    scene.colliders.push_back(sphere);
    BodyState state;
    state.position = Eigen::Vector3d(0.0, 0.0, (2 * b + 1) * kStackRadius);
    scene.initial_state.push_back(state);
  }
  scene.colliders.push_back(GroundPlane());
  Simulator sim(scene, SimulatorOptions{});
  for (int k = 0; k < steps; ++k) sim.Step();
  return sim;
}

TEST(Conversions, StampIsSimTimeButNeverZero) {
  EXPECT_EQ(StampOf(0.0), ros::TIME_MIN);
  EXPECT_FALSE(StampOf(0.0).isZero());
  EXPECT_EQ(StampOf(1.5), ros::Time(1, 500000000));
  EXPECT_LT(StampOf(0.0), StampOf(1e-4));  // still monotone after t = 0
}

TEST(Conversions, GraphNamesAreSanitised) {
  EXPECT_EQ(GraphName("big_sphere"), "big_sphere");
  EXPECT_EQ(GraphName("peg sphere/2"), "peg_sphere_2");
  EXPECT_EQ(GraphName("2nd"), "_2nd");
}

// Every frame and ~wrench/ topic belongs to one name: names that sanitise to the same frame are
// found, with both owners named; distinct names pass.
TEST(Conversions, NamesThatShareAFrameAfterSanitisingAreFound) {
  Scene scene = MakeTippeTopScene({}, {0.0, 0.0});  // "big_sphere", "peg_sphere", "ground"
  EXPECT_EQ(FrameNameClash(scene, "world"), "");
  Scene clash = scene;
  clash.colliders[1].name = "big-sphere";  // → big_sphere_contact, as the big sphere's
  EXPECT_EQ(FrameNameClash(clash, "world").rfind(
                "collision \"big-sphere\" would have the contact frame \"big_sphere_contact\" "
                "and topic ~wrench/big_sphere of collision \"big_sphere\"",
                0),
            0u)
      << FrameNameClash(clash, "world");
  Scene body_frame = scene;
  body_frame.bodies[0].name = "big_sphere_contact";  // a body frame equal to a contact frame
  EXPECT_NE(FrameNameClash(body_frame, "world").find("of body \"big_sphere_contact\""),
            std::string::npos);
  Scene world = scene;
  world.bodies[0].name = "world";  // the fixed frame
  EXPECT_NE(FrameNameClash(world, "world").find("of the fixed frame ~world_frame"),
            std::string::npos);
  // the static ground has no contact frame: a body collision may sanitise like it
  Scene ground = scene;
  ground.colliders[1].name = "ground";
  EXPECT_EQ(FrameNameClash(ground, "world"), "");
}

TEST(Conversions, LinkPoseShiftsTheCentreOfMassBack) {
  RigidBody body;
  body.com_in_link = Eigen::Vector3d(0.1, 0.0, 0.2);
  BodyState state;
  state.position = Eigen::Vector3d(1.0, 2.0, 3.0);
  state.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitZ()));
  const geometry_msgs::Pose pose = LinkPose(body, state);
  // link origin + R·com_in_link = r_S
  const Eigen::Quaterniond q(pose.orientation.w, pose.orientation.x, pose.orientation.y,
                             pose.orientation.z);
  EXPECT_LT((ToEigen(pose.position) + q * body.com_in_link - state.position).norm(), 1e-15);
  EXPECT_LT((ToEigen(pose.position) - Eigen::Vector3d(1.0, 1.9, 2.8)).norm(), 1e-15);
}

TEST(Conversions, ContactsOfARestingTopCarryForcesAsPercussionOverTimeStep) {
  const Simulator sim = RestingTop(20);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  ContactInfoArray msg;
  FillContacts(sim, StepStatistics{}, frames, &msg);
  // only the closed contact is listed: the peg's open contact is absent
  ASSERT_EQ(msg.contacts.size(), 1u);
  ASSERT_EQ(sim.contacts().size(), 1u);
  EXPECT_FALSE(Lists(msg, "peg_sphere"));
  const ContactInfo& big = msg.contacts[0];
  EXPECT_EQ(big.name, "big_sphere/ground");
  EXPECT_EQ(big.collision, "big_sphere");
  EXPECT_EQ(big.body, "tippe_top");
  EXPECT_EQ(big.other_collision, "ground");
  EXPECT_EQ(big.other_body, "");
  EXPECT_EQ(big.frame, "big_sphere_contact");
  EXPECT_EQ(big.friction_set, "sphere");
  EXPECT_TRUE(big.closed);
  EXPECT_EQ(msg.header.frame_id, "world");
  EXPECT_EQ(msg.sim_time, sim.time());
  EXPECT_EQ(msg.header.stamp, StampOf(sim.time()));
  const ContactState& c = sim.contacts()[0];
  const double dt = sim.options().time_step;
  EXPECT_EQ(big.feature, static_cast<std::uint32_t>(c.feature));
  EXPECT_EQ(big.gap, c.gap);
  EXPECT_LE(big.gap, 0.0);
  EXPECT_EQ(big.mu, c.law.mu);
  // Tippe-Top: R̄ = 3πR/16 with R = 5e-4 m (the sphere set has the drilling component)
  EXPECT_EQ(big.average_friction_radius, AverageFrictionRadius(5e-4));
  EXPECT_EQ(big.normal_percussion, c.percussion[0]);
  EXPECT_EQ(big.tangential_percussion[1], c.percussion[2]);
  EXPECT_EQ(big.drilling_percussion, c.percussion[3]);
  EXPECT_EQ(big.normal_force, c.percussion[0] / dt);
  EXPECT_EQ(big.tangential_force[0], c.percussion[1] / dt);
  EXPECT_EQ(big.drilling_torque, c.percussion[3] / dt);
  EXPECT_EQ(big.normal_velocity, c.relative_velocity[0]);
  EXPECT_EQ(big.drilling_velocity, c.relative_velocity[3]);
  // at rest the normal force carries the weight
  EXPECT_NEAR(big.normal_force, 6e-3 * 9.81, 1e-6 * 6e-3 * 9.81);
  // the normal from A (the ground) to B (the sphere); the ground's tangents are world x, y
  EXPECT_EQ(ToEigen(big.normal), Eigen::Vector3d::UnitZ());
  EXPECT_EQ(ToEigen(big.tangent1), Eigen::Vector3d::UnitX());
  EXPECT_EQ(ToEigen(big.tangent2), Eigen::Vector3d::UnitY());
  EXPECT_EQ(ToEigen(big.position), c.point);
  // the point on B: the lowest point of the big sphere, on the floor to the penetration
  EXPECT_NEAR(big.position.z, 0.0, 1e-6);
}

TEST(Conversions, AnInvertedTopListsOnlyThePegContact) {
  // upside down at rest, θ = π, lifted so that the peg (not the big sphere) touches the floor
  Scene scene = MakeTippeTopScene({}, {M_PI, 0.0});
  const TippeTopParameters p;
  scene.initial_state[0].position.z() = p.peg_offset + p.peg_radius;
  Simulator sim(scene, SimulatorOptions{});
  for (int k = 0; k < 20; ++k) sim.Step();
  ContactInfoArray msg;
  FillContacts(sim, StepStatistics{}, MakeFrameNames(sim.scene(), "world"), &msg);
  ASSERT_EQ(msg.contacts.size(), 1u);
  EXPECT_EQ(msg.contacts[0].name, "peg_sphere/ground");
  EXPECT_EQ(msg.contacts[0].collision, "peg_sphere");
  EXPECT_EQ(msg.contacts[0].frame, "peg_sphere_contact");
  EXPECT_FALSE(Lists(msg, "big_sphere"));
  EXPECT_NEAR(msg.contacts[0].normal_force, 6e-3 * 9.81, 1e-6 * 6e-3 * 9.81);
}

TEST(Conversions, ContactsBetweenTwoBodiesNameBothSides) {
  const Simulator sim = SphereStack(20);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  ContactInfoArray msg;
  FillContacts(sim, StepStatistics{}, frames, &msg);
  // lower/upper and lower/ground closed, upper/ground far open (absent)
  ASSERT_EQ(msg.contacts.size(), 2u);
  const ContactInfo* stack = nullptr;
  const ContactInfo* floor = nullptr;
  for (const ContactInfo& c : msg.contacts) {
    EXPECT_TRUE(c.closed) << c.name;
    if (c.name == "lower/upper") stack = &c;
    if (c.name == "lower/ground") floor = &c;
  }
  ASSERT_NE(stack, nullptr) << msg.contacts[0].name << ", " << msg.contacts[1].name;
  ASSERT_NE(floor, nullptr) << msg.contacts[0].name << ", " << msg.contacts[1].name;
  // the ground is A; the normal points from A to B
  EXPECT_EQ(floor->collision, "lower");
  EXPECT_EQ(floor->body, "lower_body");
  EXPECT_EQ(floor->other_collision, "ground");
  EXPECT_EQ(floor->other_body, "");
  EXPECT_EQ(ToEigen(floor->normal), Eigen::Vector3d::UnitZ());
  // body–body: both links named, B is the side the normal points to
  EXPECT_NE(stack->other_body, "");
  EXPECT_EQ(stack->collision == "lower" ? stack->body : stack->other_body, "lower_body");
  EXPECT_EQ(stack->collision == "upper" ? stack->body : stack->other_body, "upper_body");
  EXPECT_EQ(stack->collision == "upper" ? "lower" : "upper", stack->other_collision);
  const double to_b = stack->collision == "upper" ? 1.0 : -1.0;  // lower → upper is +z
  EXPECT_NEAR((ToEigen(stack->normal) - to_b * Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  // the upper body's weight through the stack, both bodies' weights through the floor
  const double g = 9.81;
  EXPECT_NEAR(stack->normal_force, kStackMass * g, 1e-5 * kStackMass * g);
  EXPECT_NEAR(floor->normal_force, 2.0 * kStackMass * g, 1e-5 * 2.0 * kStackMass * g);
  // a frame is named only where it sits: at the first contact of its collision (B's side)
  for (const ContactInfo& c : msg.contacts) {
    const ContactState* first =
        sim.FindContact(FindCollider(sim.scene(), c.collision));
    ASSERT_NE(first, nullptr);
    const bool is_first = ContactName(sim.scene(), *first) == c.name;
    EXPECT_EQ(c.frame, is_first ? c.collision + "_contact" : std::string()) << c.name;
  }
}

TEST(Conversions, WrenchIsTheContactForceInTheContactFrame) {
  const Simulator sim = RestingTop(20);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  // one slot per collider on a body, in scene order
  ASSERT_EQ(frames.slots, (std::vector<int>{kBigSphere, kPegSphere}));
  EXPECT_EQ(frames.contacts, (std::vector<std::string>{"big_sphere_contact", "peg_sphere_contact"}));
  geometry_msgs::WrenchStamped wrench;
  EXPECT_TRUE(FillWrench(sim, 0, frames, StampOf(sim.time()), &wrench));
  const Eigen::Vector4d lambda = sim.contacts()[0].percussion / sim.options().time_step;
  EXPECT_EQ(wrench.header.frame_id, "big_sphere_contact");
  EXPECT_EQ(wrench.header.stamp, StampOf(sim.time()));
  // one contact: its force and drilling torque at it, in its (t1, t2, n) axes
  EXPECT_DOUBLE_EQ(wrench.wrench.force.z, lambda[0]);
  EXPECT_DOUBLE_EQ(wrench.wrench.force.x, lambda[1]);
  EXPECT_DOUBLE_EQ(wrench.wrench.force.y, lambda[2]);
  EXPECT_DOUBLE_EQ(wrench.wrench.torque.z, lambda[3]);
  EXPECT_EQ(wrench.wrench.torque.x, 0.0);
  EXPECT_EQ(wrench.wrench.torque.y, 0.0);
  EXPECT_NEAR(wrench.wrench.force.z, 6e-3 * 9.81, 1e-6 * 6e-3 * 9.81);
  // the peg has no contact: zero, in its own frame
  wrench.wrench.force.z = 1.0;
  EXPECT_FALSE(FillWrench(sim, 1, frames, StampOf(sim.time()), &wrench));
  EXPECT_EQ(wrench.header.frame_id, "peg_sphere_contact");
  EXPECT_EQ(ToEigen(wrench.wrench.force), Eigen::Vector3d::Zero());
  EXPECT_EQ(ToEigen(wrench.wrench.torque), Eigen::Vector3d::Zero());
}

TEST(Conversions, ARollingContactCarriesItsRollingTorque) {
  // the lower sphere of the stack with rolling resistance, rolling along x: its ground contact
  // has the rolling components, the message and the slot's wrench carry Λ_R
  Scene scene = SphereStack(0).scene();
  for (Collider& c : scene.colliders) {
    if (c.body == kWorld) continue;
    c.law.friction_set = FrictionSet::kRollingDecoupled;
    c.law.rolling_resistance = 1e-3f;
  }
  scene.bodies.resize(1);
  scene.colliders = {scene.colliders[0], scene.colliders[2]};
  scene.initial_state.resize(1);
  scene.initial_state[0].linear_velocity = Eigen::Vector3d(0.1, 0.0, 0.0);
  scene.initial_state[0].angular_velocity = Eigen::Vector3d(0.0, 0.1 / kStackRadius, 0.0);
  Simulator rolling(scene, SimulatorOptions{});
  for (int k = 0; k < 20; ++k) rolling.Step();
  ASSERT_EQ(rolling.contacts().size(), 1u);
  const ContactState& c = rolling.contacts()[0];
  ASSERT_EQ(c.dimension, 6);
  const double dt = rolling.options().time_step;
  // the rolling torque opposes the roll about t2 = ŷ and sits on its bound μ_rΛ_N
  EXPECT_LT(c.rolling_percussion[1], 0.0);
  EXPECT_NEAR(c.rolling_percussion.norm(), 1e-3f * c.percussion[0], 1e-9 * c.percussion[0]);
  const FrameNames frames = MakeFrameNames(rolling.scene(), "world");
  ContactInfoArray msg;
  FillContacts(rolling, StepStatistics{}, frames, &msg);
  ASSERT_EQ(msg.contacts.size(), 1u);
  EXPECT_EQ(msg.contacts[0].rolling_resistance, static_cast<double>(1e-3f));
  EXPECT_EQ(msg.contacts[0].rolling_percussion[0], c.rolling_percussion[0]);
  EXPECT_EQ(msg.contacts[0].rolling_percussion[1], c.rolling_percussion[1]);
  EXPECT_EQ(msg.contacts[0].rolling_torque[1], c.rolling_percussion[1] / dt);
  geometry_msgs::WrenchStamped wrench;
  ASSERT_TRUE(FillWrench(rolling, 0, frames, StampOf(rolling.time()), &wrench));
  // in the contact frame's axes (t1, t2, n): the rolling torque about x and y, drilling about z
  EXPECT_NEAR(wrench.wrench.torque.x, c.rolling_percussion[0] / dt, 1e-12);
  EXPECT_NEAR(wrench.wrench.torque.y, c.rolling_percussion[1] / dt, 1e-12);
  // the rolling arrow: Λ_R/Δt in the tangent plane, scaled as the drilling arrow
  visualization_msgs::MarkerArray markers;
  FillMarkers(rolling, frames, StampOf(rolling.time()), 0.5, 1000.0, 0, &markers);
  ASSERT_EQ(markers.markers.size(), kMarkersPerContact);
  const visualization_msgs::Marker& arrow = markers.markers[2];
  EXPECT_EQ(arrow.ns, "rolling_torque");
  EXPECT_EQ(arrow.action, visualization_msgs::Marker::ADD);
  ASSERT_EQ(arrow.points.size(), 2u);
  const Eigen::Vector3d tau = (c.rolling_percussion[0] * c.frame.tangent1 +
                               c.rolling_percussion[1] * c.frame.tangent2) /
                              dt;
  EXPECT_LT((ToEigen(arrow.points[1]) - ToEigen(arrow.points[0]) - 1000.0 * tau).norm(), 1e-12);
  EXPECT_GT(tau.norm(), 0.0);
  // without rolling resistance the fields are zero
  const Simulator stack = SphereStack(20);
  ContactInfoArray plain;
  FillContacts(stack, StepStatistics{}, MakeFrameNames(stack.scene(), "world"), &plain);
  ASSERT_EQ(plain.contacts.size(), 2u);
  for (const ContactInfo& info : plain.contacts) {
    EXPECT_EQ(info.rolling_resistance, 0.0);
    EXPECT_EQ(info.rolling_torque[0], 0.0);
    EXPECT_EQ(info.rolling_torque[1], 0.0);
  }
}

TEST(Conversions, WrenchSumsTheContactsOfOneCollider) {
  // the lower sphere of the stack: pushed up by the floor, down by the upper sphere
  const Simulator sim = SphereStack(20);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  ASSERT_EQ(frames.contacts, (std::vector<std::string>{"lower_contact", "upper_contact"}));
  tf2_msgs::TFMessage tf;
  AppendTransforms(sim, frames, StampOf(sim.time()), &tf);
  ASSERT_EQ(tf.transforms.size(), 4u);  // two links, two slots
  const auto& lower_frame = tf.transforms[2];
  ASSERT_EQ(lower_frame.child_frame_id, "lower_contact");
  const Eigen::Quaterniond axes = ToEigen(lower_frame.transform.rotation);
  const Eigen::Vector3d origin = ToEigen(lower_frame.transform.translation);

  geometry_msgs::WrenchStamped wrench;
  EXPECT_TRUE(FillWrench(sim, 0, frames, StampOf(sim.time()), &wrench));
  EXPECT_EQ(wrench.header.frame_id, "lower_contact");
  // the net contact force on the lower sphere carries its own weight only
  const Eigen::Vector3d force_world = axes * ToEigen(wrench.wrench.force);
  const double g = 9.81;
  EXPECT_LT((force_world - Eigen::Vector3d(0.0, 0.0, kStackMass * g)).norm(), 1e-5 * kStackMass * g)
      << force_world.transpose();
  // at rest the contact forces have no moment about the centre S: about the frame's origin it is
  // (r_S - origin) x F
  const Eigen::Vector3d torque_world = axes * ToEigen(wrench.wrench.torque);
  const Eigen::Vector3d expected = (sim.state()[0].position - origin).cross(force_world);
  EXPECT_LT((torque_world - expected).norm(), 1e-9) << torque_world.transpose();
  // the frame sits at one of the lower sphere's contacts, axes (t1, t2, n)
  const ContactState* first = sim.FindContact(0);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(origin, first->point);
  EXPECT_LT((axes * Eigen::Vector3d::UnitZ() - first->frame.normal).norm(), 1e-12);
  EXPECT_LT((axes * Eigen::Vector3d::UnitX() - first->frame.tangent1).norm(), 1e-12);

  // the upper sphere: one contact, its weight
  EXPECT_TRUE(FillWrench(sim, 1, frames, StampOf(sim.time()), &wrench));
  const Eigen::Quaterniond upper_axes = ToEigen(tf.transforms[3].transform.rotation);
  EXPECT_LT((upper_axes * ToEigen(wrench.wrench.force) - Eigen::Vector3d(0.0, 0.0, kStackMass * g))
                .norm(),
            1e-5 * kStackMass * g);
}

TEST(Conversions, TransformsPlaceTheLinkAndTheContactFrames) {
  const Simulator sim = RestingTop(5);
  const FrameNames frames = MakeFrameNames(sim.scene(), "odom_free");
  tf2_msgs::TFMessage tf;
  AppendTransforms(sim, frames, StampOf(sim.time()), &tf);
  ASSERT_EQ(tf.transforms.size(), 3u);
  EXPECT_EQ(tf.transforms[0].header.frame_id, "odom_free");
  EXPECT_EQ(tf.transforms[0].child_frame_id, "tippe_top");
  EXPECT_EQ(tf.transforms[0].transform.translation.z, sim.state()[0].position.z());
  // the big sphere's slot: at its contact point, axes (t1, t2, n) = world x, y, z
  EXPECT_EQ(tf.transforms[1].child_frame_id, "big_sphere_contact");
  ASSERT_EQ(sim.contacts().size(), 1u);
  EXPECT_EQ(ToEigen(tf.transforms[1].transform.translation), sim.contacts()[0].point);
  EXPECT_LT(ToEigen(tf.transforms[1].transform.rotation).angularDistance(
                Eigen::Quaterniond::Identity()),
            1e-12);
  // the peg's slot without a contact: at the peg sphere's centre, world axes
  EXPECT_EQ(tf.transforms[2].child_frame_id, "peg_sphere_contact");
  const TippeTopParameters p;
  const Eigen::Vector3d peg_centre =
      sim.state()[0].position + sim.state()[0].orientation * Eigen::Vector3d(0, 0, p.peg_offset);
  EXPECT_LT((ToEigen(tf.transforms[2].transform.translation) - peg_centre).norm(), 1e-15);
  EXPECT_EQ(ToEigen(tf.transforms[2].transform.rotation).coeffs(),
            Eigen::Quaterniond::Identity().coeffs());
  for (const auto& t : tf.transforms) {
    EXPECT_EQ(t.header.stamp, StampOf(sim.time()));
    EXPECT_EQ(t.header.frame_id, "odom_free");
  }
}

TEST(Conversions, TransformsOfALaterStampFollowTheEarlierOnes) {
  // /tf batches several samples in one message: a second append keeps the first one intact
  Simulator sim = RestingTop(5);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  tf2_msgs::TFMessage tf;
  AppendTransforms(sim, frames, StampOf(sim.time()), &tf);
  const tf2_msgs::TFMessage first = tf;
  const ros::Time first_stamp = StampOf(sim.time());
  for (int i = 0; i < 10; ++i) sim.Step();
  AppendTransforms(sim, frames, StampOf(sim.time()), &tf);
  tf2_msgs::TFMessage second;
  AppendTransforms(sim, frames, StampOf(sim.time()), &second);
  ASSERT_EQ(tf.transforms.size(), first.transforms.size() + second.transforms.size());
  ASSERT_GT(StampOf(sim.time()), first_stamp);
  for (std::size_t i = 0; i < first.transforms.size(); ++i) {
    EXPECT_EQ(tf.transforms[i], first.transforms[i]) << i;
  }
  for (std::size_t i = 0; i < second.transforms.size(); ++i) {
    EXPECT_EQ(tf.transforms[first.transforms.size() + i], second.transforms[i]) << i;
  }
}

TEST(Conversions, StateAgreesWithTheCoreFunctions) {
  Simulator sim(MakeTippeTopScene(), SimulatorOptions{});
  for (int k = 0; k < 100; ++k) sim.Step();
  SimulationState msg;
  FillState(sim, true, "world", &msg);
  ASSERT_EQ(msg.bodies.size(), 1u);
  const BodyInfo& b = msg.bodies[0];
  const BodyState& s = sim.state()[0];
  EXPECT_EQ(msg.sim_time, sim.time());
  EXPECT_TRUE(msg.paused);
  EXPECT_EQ(msg.energy, sim.Energy());
  EXPECT_EQ(b.inclination, Inclination(s));
  // of the body's first sphere collider, the big sphere
  EXPECT_EQ(b.jellett_integral, JellettIntegral(sim.scene(), sim.state(), kBigSphere));
  EXPECT_TRUE(std::isfinite(b.jellett_integral));
  const Eigen::Vector3d omega = s.orientation * s.angular_velocity;
  EXPECT_LT((ToEigen(b.twist.angular) - omega).norm(), 1e-12);
  EXPECT_EQ(b.vertical_spin, b.twist.angular.z);
  EXPECT_EQ(ToEigen(b.angular_velocity_body), s.angular_velocity);
  EXPECT_EQ(ToEigen(b.center_of_mass), s.position);
  EXPECT_EQ(ToEigen(b.twist.linear), s.linear_velocity);
  // the Tippe-Top's link frame is its body frame
  EXPECT_EQ(ToEigen(b.pose.position), s.position);
}

TEST(Conversions, MarkersDrawClosedContactsAndDeleteOpenOnes) {
  const Simulator sim = RestingTop(20);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  ASSERT_EQ(sim.contacts().size(), 1u);
  visualization_msgs::MarkerArray markers;
  // the previous message drew two contacts (say, both spheres): id 1 is deleted now
  FillMarkers(sim, frames, StampOf(sim.time()), 0.5, 1000.0, 2, &markers);
  ASSERT_EQ(markers.markers.size(), 2 * kMarkersPerContact);
  const visualization_msgs::Marker& force = markers.markers[0];
  EXPECT_EQ(force.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(force.ns, "contact_force");
  EXPECT_EQ(force.id, 0);
  EXPECT_EQ(force.header.frame_id, "world");
  ASSERT_EQ(force.points.size(), 2u);
  const Eigen::Vector3d tail = ToEigen(force.points[0]);
  const Eigen::Vector3d head = ToEigen(force.points[1]);
  EXPECT_EQ(tail, sim.contacts()[0].point);
  const double lambda_n = sim.contacts()[0].percussion[0] / sim.options().time_step;
  EXPECT_NEAR(head.z() - tail.z(), 0.5 * lambda_n, 1e-15);
  const visualization_msgs::Marker& torque = markers.markers[1];
  EXPECT_EQ(torque.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(torque.ns, "drilling_torque");
  EXPECT_EQ(torque.id, 0);
  // the sphere set has no rolling components: its rolling arrow is deleted
  EXPECT_EQ(markers.markers[2].ns, "rolling_torque");
  EXPECT_EQ(markers.markers[2].action, visualization_msgs::Marker::DELETE);
  for (std::size_t k = kMarkersPerContact; k < 2 * kMarkersPerContact; ++k) {
    EXPECT_EQ(markers.markers[k].action, visualization_msgs::Marker::DELETE) << k;
    EXPECT_EQ(markers.markers[k].id, 1) << k;
  }
  EXPECT_EQ(markers.markers[3].ns, "contact_force");
  EXPECT_EQ(markers.markers[4].ns, "drilling_torque");
  EXPECT_EQ(markers.markers[5].ns, "rolling_torque");
  // nothing drawn before: only the one contact's arrows (the reused message shrinks)
  FillMarkers(sim, frames, StampOf(sim.time()), 0.5, 1000.0, 0, &markers);
  ASSERT_EQ(markers.markers.size(), kMarkersPerContact);
  EXPECT_EQ(markers.markers[0].action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(markers.markers[1].action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(DeleteAllMarkers("world").markers.at(0).action,
            visualization_msgs::Marker::DELETEALL);
}

}  // namespace
}  // namespace nonsmooth_sim::node
