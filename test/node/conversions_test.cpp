// Core -> messages: stamps never 0, forces are percussions / Δt in the contact frame, the link
// pose accounts for the centre-of-mass offset, state fields agree with the core's functions.
#include <gtest/gtest.h>

#include <cmath>

#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/node/conversions.h"

namespace nonsmooth_sim::node {
namespace {

Eigen::Vector3d ToEigen(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
Eigen::Vector3d ToEigen(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

// the Tippe-Top upright at rest on its big sphere, after `steps` steps
Simulator RestingTop(int steps) {
  Simulator sim(MakeTippeTopScene({}, {0.0, 0.0}), SimulatorOptions{});
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
  ASSERT_EQ(msg.contacts.size(), 2u);
  const ContactInfo& big = msg.contacts[0];
  const ContactInfo& peg = msg.contacts[1];
  EXPECT_EQ(big.name, "big_sphere");
  EXPECT_EQ(big.body, "tippe_top");
  EXPECT_EQ(big.frame, "big_sphere_contact");
  EXPECT_EQ(big.friction_set, "sphere");
  EXPECT_TRUE(big.closed);
  EXPECT_FALSE(peg.closed);
  EXPECT_EQ(msg.header.frame_id, "world");
  EXPECT_EQ(msg.sim_time, sim.time());
  EXPECT_EQ(msg.header.stamp, StampOf(sim.time()));
  const ContactState& c = sim.contacts()[0];
  const double dt = sim.options().time_step;
  EXPECT_EQ(big.normal_percussion, c.percussion[0]);
  EXPECT_EQ(big.normal_force, c.percussion[0] / dt);
  EXPECT_EQ(big.tangential_force[0], c.percussion[1] / dt);
  EXPECT_EQ(big.drilling_torque, c.percussion[3] / dt);
  EXPECT_EQ(big.normal_velocity, c.relative_velocity[0]);
  // at rest the normal force carries the weight
  EXPECT_NEAR(big.normal_force, 6e-3 * 9.81, 1e-6 * 6e-3 * 9.81);
  EXPECT_EQ(ToEigen(big.normal), Eigen::Vector3d::UnitZ());
  EXPECT_EQ(ToEigen(big.tangent1), Eigen::Vector3d::UnitX());
  EXPECT_EQ(ToEigen(big.tangent2), Eigen::Vector3d::UnitY());
  EXPECT_EQ(ToEigen(big.position), c.point);
}

TEST(Conversions, WrenchIsTheContactForceInTheContactFrame) {
  const Simulator sim = RestingTop(20);
  const FrameNames frames = MakeFrameNames(sim.scene(), "world");
  geometry_msgs::WrenchStamped wrench;
  FillWrench(sim, 0, frames, StampOf(sim.time()), &wrench);
  const Eigen::Vector4d lambda = sim.contacts()[0].percussion / sim.options().time_step;
  EXPECT_EQ(wrench.header.frame_id, "big_sphere_contact");
  EXPECT_EQ(wrench.wrench.force.z, lambda[0]);
  EXPECT_EQ(wrench.wrench.force.x, lambda[1]);
  EXPECT_EQ(wrench.wrench.force.y, lambda[2]);
  EXPECT_EQ(wrench.wrench.torque.z, lambda[3]);
  FillWrench(sim, 1, frames, StampOf(sim.time()), &wrench);  // the open peg contact
  EXPECT_EQ(wrench.wrench.force.z, 0.0);
  EXPECT_EQ(wrench.header.frame_id, "peg_sphere_contact");
}

TEST(Conversions, TransformsPlaceTheLinkAndTheContactFrames) {
  const Simulator sim = RestingTop(5);
  const FrameNames frames = MakeFrameNames(sim.scene(), "odom_free");
  tf2_msgs::TFMessage tf;
  FillTransforms(sim, frames, StampOf(sim.time()), &tf);
  ASSERT_EQ(tf.transforms.size(), 3u);
  EXPECT_EQ(tf.transforms[0].header.frame_id, "odom_free");
  EXPECT_EQ(tf.transforms[0].child_frame_id, "tippe_top");
  EXPECT_EQ(tf.transforms[0].transform.translation.z, sim.state()[0].position.z());
  EXPECT_EQ(tf.transforms[1].child_frame_id, "big_sphere_contact");
  EXPECT_EQ(tf.transforms[1].transform.translation.z, sim.contacts()[0].point.z());
  EXPECT_EQ(tf.transforms[2].child_frame_id, "peg_sphere_contact");
  for (const auto& t : tf.transforms) EXPECT_EQ(t.header.stamp, StampOf(sim.time()));
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
  EXPECT_EQ(b.jellett_integral, JellettIntegral(sim.scene(), sim.state(), 0));
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
  visualization_msgs::MarkerArray markers;
  FillMarkers(sim, frames, StampOf(sim.time()), 0.5, 1000.0, &markers);
  ASSERT_EQ(markers.markers.size(), 4u);
  const visualization_msgs::Marker& force = markers.markers[0];
  EXPECT_EQ(force.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(force.ns, "contact_force");
  ASSERT_EQ(force.points.size(), 2u);
  const Eigen::Vector3d tail = ToEigen(force.points[0]);
  const Eigen::Vector3d head = ToEigen(force.points[1]);
  EXPECT_EQ(tail, sim.contacts()[0].point);
  const double lambda_n = sim.contacts()[0].percussion[0] / sim.options().time_step;
  EXPECT_NEAR(head.z() - tail.z(), 0.5 * lambda_n, 1e-15);
  EXPECT_EQ(markers.markers[2].action, visualization_msgs::Marker::DELETE);  // peg: open
  EXPECT_EQ(markers.markers[3].action, visualization_msgs::Marker::DELETE);
  EXPECT_EQ(DeleteAllMarkers("world").markers.at(0).action,
            visualization_msgs::Marker::DELETEALL);
}

}  // namespace
}  // namespace nonsmooth_sim::node
