// Resting contact of every shape, built in code (no URDF): a body of each shape dropped on the
// ground comes to rest; a box on a 20° incline sticks or slides as Coulomb says; a stack of three
// bodies stays stacked. docs/scenes.md section 7.
//
// Bodies are uniform (ShapeVolume, ShapeUnitInertia), 0.1 kg; μ = 0.5, R = 0.5 mm (R̄ = 3πR/16),
// ε = 0; Δt = 1e-4 s (the 5 mm drop lands at 0.31 m/s: 31 µm per step, the impact's penetration
// at the midpoint is below ½·31 µm); runs of 2 s.
//
// "At rest" is asserted on the largest speed of any point of the body, |v_S| + |ω|·(its extent),
// "no drift" on the displacement between t = 1 s and 2 s, "penetration" on the deepest closed
// contact of the last step (StepStatistics::max_penetration): the gap correction holds a resting
// contact at kGapCorrectionSlop = 1e-6 m, so ≤ 1e-6 m up to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/constants.h"
#include "scene_test_support.h"

namespace nonsmooth_sim {
namespace {

using scene_test::MaxPointSpeed;
using scene_test::Runner;

constexpr double kG = 9.81;
// the slop, and round-off of the second contact of a body resting on two (a capsule on its side:
// measured 1.00002e-6 m, its ends' heights differ by 2e-11 m)
constexpr double kPenetrationBound = kGapCorrectionSlop + 1e-10;

ContactLaw Law(double mu) {
  ContactLaw law;
  law.mu = mu;
  law.rbar = 3.0 * kPi * 5e-4 / 16.0;
  return law;
}

RigidBody UniformBody(const std::string& name, const Shape& shape, double mass) {
  RigidBody body;
  body.name = name;
  body.mass = mass;
  body.inertia = mass / ShapeVolume(shape) * ShapeUnitInertia(shape);
  return body;
}

// Height of the shape frame's origin above the plane z = 0 at which the shape, turned by
// `orientation`, just touches it [m].
double TouchingHeight(const Shape& shape, const Eigen::Quaterniond& orientation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = orientation.toRotationMatrix();
  ContactGeometry g[kMaxPairContacts];
  const int n = CollisionTable::Defaults().Collide(Shape::Plane(), Eigen::Isometry3d::Identity(),
                                                   shape, pose, 1.0, g);
  double lowest = 1.0;
  for (int i = 0; i < n; ++i) lowest = std::min(lowest, g[i].gap);
  return -lowest;
}

// One body of `shape` on the ground, `drop` above touching, at rest.
Scene DropScene(const Shape& shape, const Eigen::Quaterniond& orientation, double drop) {
  Scene scene;
  scene.bodies.push_back(UniformBody("body", shape, 0.1));
  Collider c;
  c.name = "shape";
  c.body = 0;
  c.shape = shape;
  c.law = Law(0.5);
  scene.colliders = {c, GroundPlane()};
  BodyState s;
  s.orientation = orientation;
  s.position = Eigen::Vector3d(0.0, 0.0, TouchingHeight(shape, orientation) + drop);
  scene.initial_state = {s};
  return scene;
}

struct Settled {
  double speed = 0.0;        // largest point speed at t = 2 s [m/s]
  double penetration = 0.0;  // deepest contact of the last step [m]
  double drift = 0.0;        // |r_S(2 s) − r_S(1 s)| [m]
  double height_error = 0.0; // z_S(2 s) − touching height [m]
  int switches_late = 0;     // changes of the contact set over [1, 2] s
  double max_energy_excess = 0.0;
  bool finite = true;
};

// `tolerance_rel`: the solver's; 1e-8 where the energy check is about the scheme (the default 1e-5
// leaves an energy error of 3.6e-14 J at the capsule's two-contact impact, 6e-15 J beyond the
// round-off allowance; gone at 1e-8).
Settled Settle(const Scene& scene, double rest_height, double tolerance_rel) {
  SimulatorOptions options;
  options.time_step = 1e-4;
  options.solver.tolerance_rel = tolerance_rel;
  Simulator sim(scene, options);
  Runner run(&sim);
  run.RunUntil(1.0);
  const Eigen::Vector3d at_1s = sim.state()[0].position;
  long signature = -1;
  Settled r;
  while (sim.time() < 2.0 && run.finite()) {
    run.Step();
    long sig = 0;
    for (const ContactState& c : sim.contacts()) sig = sig * 32 + c.feature + 1;
    if (signature >= 0 && sig != signature) ++r.switches_late;
    signature = sig;
  }
  r.speed = MaxPointSpeed(sim.scene(), sim.state(), 0);
  r.penetration = run.last().max_penetration;
  r.drift = (sim.state()[0].position - at_1s).norm();
  r.height_error = sim.state()[0].position.z() - rest_height;
  r.max_energy_excess = run.max_energy_excess();
  r.finite = run.finite();
  return r;
}

struct NamedShape {
  const char* name;
  Shape shape;
  Eigen::Quaterniond resting;  // an orientation it rests in (a capsule on its side)
};

std::vector<NamedShape> Shapes() {
  const Eigen::Quaterniond upright = Eigen::Quaterniond::Identity();
  const Eigen::Quaterniond on_side(Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitX()));
  return {{"sphere", Shape::Sphere(0.01), upright},
          {"ellipsoid", Shape::Ellipsoid(Eigen::Vector3d(0.02, 0.015, 0.01)), upright},
          {"cylinder", Shape::Cylinder(0.015, 0.005), upright},
          {"box", Shape::Box(Eigen::Vector3d(0.02, 0.015, 0.01)), upright},
          {"capsule", Shape::Capsule(0.008, 0.015), on_side}};
}

// Dropped 5 mm in a resting orientation (the ellipsoid on its shortest axis, the capsule on its
// side, cylinder and box on a face), every shape comes to rest: after 1 s its points move below
// 1e-6 m/s, its contact is at most 1e-6 m deep, it does not drift (measured: all at rest to
// round-off, 1e-6 m deep (the slop), no drift, no contact change). Solver tolerance_rel = 1e-8
// (see Settle).
TEST(RestingContact, DropEachShapeComesToRest) {
  for (const NamedShape& s : Shapes()) {
    const Scene scene = DropScene(s.shape, s.resting, 0.005);
    const Settled r = Settle(scene, TouchingHeight(s.shape, s.resting), 1e-8);
    std::printf("%-9s speed %.2e m/s, penetration %.2e m, drift %.2e m, z error %.2e m, %d late "
                "contact changes\n",
                s.name, r.speed, r.penetration, r.drift, r.height_error, r.switches_late);
    EXPECT_LT(r.speed, 1e-6) << s.name;
    EXPECT_LE(r.penetration, kPenetrationBound) << s.name;
    EXPECT_LT(r.drift, 1e-9) << s.name;
    EXPECT_GT(r.height_error, -kPenetrationBound) << s.name << " sinks";
    EXPECT_EQ(r.switches_late, 0) << s.name << " jitters";
    EXPECT_LE(r.max_energy_excess, 0.0) << s.name;
    EXPECT_TRUE(r.finite) << s.name;
  }
}

// Dropped 5 mm with a tilt of 0.05 rad (about (1, 1, 0)/√2), box, cylinder and capsule land on a
// corner / rim / end first and must settle on their face / side the same way.
//
// Measured: the cylinder and the box rest on their four face points (plane_cylinder.h,
// plane_box.h), levelled to the slop (1e-6 m) by the gap correction (LevelOnPoints), speeds
// ~1e-19 m/s, no drift; the capsule rests on its two ends at the slop, still rolling at 2e-8 m/s
// (a capsule on its side is neutrally stable: no rolling resistance), 5e-9 m in 1 s, hence its
// drift bound of 1e-8 m. (Before the face points and the levelling, a disc here rocked for ever
// between one patch at its face centre and its rim, and the capsule rested with one end
// 8.7e-6 m deep.)
// Solver tolerance_rel = 1e-8 (see Settle; with 1e-5 the capsule also creeps at ~1e-8 m/s).
TEST(RestingContact, DropTiltedOntoFace) {
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, 1, 0).normalized()));
  for (const NamedShape& s : Shapes()) {
    const std::string name = s.name;
    if (name == "sphere" || name == "ellipsoid") continue;  // these rock or roll: no dissipation
    const Scene scene = DropScene(s.shape, tilt * s.resting, 0.005);
    const Settled r = Settle(scene, TouchingHeight(s.shape, s.resting), 1e-8);
    std::printf("%-9s tilted: speed %.2e m/s, penetration %.2e m, drift %.2e m, z error %.2e m, "
                "%d late contact changes\n",
                s.name, r.speed, r.penetration, r.drift, r.height_error, r.switches_late);
    EXPECT_LT(r.speed, 1e-6) << s.name;
    EXPECT_LE(r.penetration, 2.0 * kPenetrationBound) << s.name;
    EXPECT_LT(r.drift, name == "capsule" ? 1e-8 : 1e-9) << s.name;
    EXPECT_EQ(r.switches_late, 0) << s.name << " jitters";
    EXPECT_TRUE(r.finite) << s.name;
  }
}

// A box (0.04 × 0.03 × 0.02 m) on a plane inclined by 20° (a static plane collider turned about y;
// no ground), released at rest with its bottom face on the plane: with μ = 0.5 > tan 20° = 0.364 it
// sticks, with μ = 0.2 it slides with a = g (sin 20° − 0.2 cos 20°) = 1.5115 m/s² (fitted slope
// of the speed along the incline over [0.05, 0.5] s).
struct Incline {
  double acceleration = 0.0;     // along the incline, downwards [m/s²]
  double normal_speed_start = 0.0;  // max |v_S·n| over the first 10 ms [m/s]
  double normal_speed_late = 0.0;   // max |v_S·n| after 10 ms [m/s]
  double creep = 0.0;            // |r_S(0.5 s) − r_S(0.05 s)| [m]
  double max_energy_excess = 0.0;
  bool finite = true;
};

Incline RunIncline(double mu) {
  const double angle = 20.0 * kPi / 180.0;
  const Eigen::Quaterniond incline(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d normal = incline * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d down_slope = incline * Eigen::Vector3d::UnitX();  // (cos, 0, −sin)
  const Shape box = Shape::Box(Eigen::Vector3d(0.02, 0.015, 0.01));
  Scene scene;
  scene.bodies.push_back(UniformBody("box", box, 0.1));
  Collider body;
  body.name = "box";
  body.body = 0;
  body.shape = box;
  body.law = Law(mu);
  Collider plane;
  plane.name = "incline";
  plane.body = kWorld;
  plane.shape = Shape::Plane();
  plane.pose.linear() = incline.toRotationMatrix();
  plane.law = GroundLaw();
  scene.colliders = {body, plane};
  BodyState s;
  s.orientation = incline;
  s.position = 0.01 * normal;  // the bottom face on the plane
  scene.initial_state = {s};
  SimulatorOptions options;
  options.time_step = 1e-4;
  Simulator sim(scene, options);
  Runner run(&sim);
  std::vector<double> t, v;
  Incline r;
  Eigen::Vector3d at_50ms = Eigen::Vector3d::Zero();
  while (sim.time() < 0.5 && run.finite()) {
    run.Step();
    const BodyState& b = sim.state()[0];
    const double vn = std::abs(b.linear_velocity.dot(normal));
    if (sim.time() < 0.01) {
      r.normal_speed_start = std::max(r.normal_speed_start, vn);
    } else {
      r.normal_speed_late = std::max(r.normal_speed_late, vn);
    }
    if (sim.time() < 0.05) continue;
    if (t.empty()) at_50ms = b.position;
    t.push_back(sim.time());
    v.push_back(b.linear_velocity.dot(down_slope));
  }
  r.creep = (sim.state()[0].position - at_50ms).norm();
  r.max_energy_excess = run.max_energy_excess();
  r.finite = run.finite();
  const double n = static_cast<double>(t.size());
  double st = 0, sv = 0, stt = 0, stv = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    st += t[i];
    sv += v[i];
    stt += t[i] * t[i];
    stv += t[i] * v[i];
  }
  r.acceleration = (n * stv - st * sv) / (n * stt - st * st);
  std::printf("mu = %.1f: a = %.6f m/s^2, creep over [0.05, 0.5] s %.2e m, max normal speed "
              "%.2e m/s in the first 10 ms, %.2e m/s after\n",
              mu, r.acceleration, r.creep, r.normal_speed_start, r.normal_speed_late);
  return r;
}

// Measured: μ = 0.5: a = 4e-20 m/s², no creep; μ = 0.2: a = 1.51154 m/s² (relative error 6e-14).
// Both settle on four corners within 4 ms (see FlatFaceOnInclineDoesNotHop) and slide or stick
// without leaving the plane afterwards.
TEST(RestingContact, BoxOnInclineSticksOrSlides) {
  const double angle = 20.0 * kPi / 180.0;
  const Incline stick = RunIncline(0.5);
  EXPECT_LT(std::abs(stick.acceleration), 1e-9);
  EXPECT_LT(stick.creep, 1e-9);
  EXPECT_LT(stick.normal_speed_late, 1e-6);
  EXPECT_TRUE(stick.finite);
  const Incline slide = RunIncline(0.2);
  const double expected = kG * (std::sin(angle) - 0.2 * std::cos(angle));
  EXPECT_NEAR(slide.acceleration / expected, 1.0, 0.01);
  EXPECT_LT(slide.normal_speed_late, 1e-6);  // it slides, it does not hop
  EXPECT_TRUE(slide.finite);
}

// Released with its face flat on the incline, the box does not hop.
//
// Measured: no hop (it did with one patch at the face centre, and while round-off left some face
// points open: kContactHysteresis and the shared face gap, plane_box.h, fixed both).
TEST(RestingContact, FlatFaceOnInclineDoesNotHop) {
  const Incline stick = RunIncline(0.5);
  EXPECT_LT(stick.normal_speed_start, 1e-6);
  EXPECT_LE(stick.max_energy_excess, 0.0);
  const Incline slide = RunIncline(0.2);
  EXPECT_LT(slide.normal_speed_start, 1e-6);
  EXPECT_LE(slide.max_energy_excess, 0.0);
}

// A stack of three: a log pile of capsules (r = 0.01 m, l = 0.03 m, axes along x), two side by
// side on the ground touching each other, the third in the groove on top (centres 2r apart:
// z = r + √3 r), dropped 0.5 mm into it. It stays stacked, at rest, without sinking.
//
// The pile has one zero-stiffness mode: the whole pile translating sideways with the bottom logs
// rolling on the ground and the top one counter-rotating (a board on two rollers); any residual
// horizontal force accelerates it. With the solver's default tolerance_rel = 1e-5 it creeps
// (measured: all three at −9.3e-8 m/s along y after 1 s, accelerating at ~1e-7 m/s², max point
// speed 9.8e-7 m/s at 2 s); with tolerance_rel = 1e-10 it does not (6e-12 m/s). The rest
// positions are met to a few slops: the top log sits 2.3e-6 m low, pushing the bottom ones
// 0.9e-6 m apart (each contact held at about −kGapCorrectionSlop).
void CheckStack(double tolerance_rel, double speed_bound) {
  const double r = 0.01;
  const Shape log = Shape::Capsule(r, 0.03);
  const Eigen::Quaterniond along_x(Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d rest[3] = {{0.0, -r, r}, {0.0, r, r}, {0.0, 0.0, r + std::sqrt(3.0) * r}};
  Scene scene;
  for (int k = 0; k < 3; ++k) {
    scene.bodies.push_back(UniformBody("log" + std::to_string(k), log, 0.04));
    Collider c;
    c.name = "log" + std::to_string(k);
    c.body = k;
    c.shape = log;
    c.law = Law(0.5);
    scene.colliders.push_back(c);
    BodyState s;
    s.orientation = along_x;
    s.position = rest[k] + Eigen::Vector3d(0.0, 0.0, k == 2 ? 0.0005 : 0.0);
    scene.initial_state.push_back(s);
  }
  scene.colliders.push_back(GroundPlane());
  SimulatorOptions options;
  options.time_step = 1e-4;
  options.solver.tolerance_rel = tolerance_rel;
  Simulator sim(scene, options);
  Runner run(&sim);
  run.RunUntil(2.0);
  for (int k = 0; k < 3; ++k) {
    const BodyState& s = sim.state()[static_cast<std::size_t>(k)];
    const double speed = MaxPointSpeed(sim.scene(), sim.state(), k);
    const Eigen::Vector3d offset = s.position - rest[k];
    std::printf("log %d: offset from rest (%.2e %.2e %.2e) m, max point speed %.2e m/s\n", k,
                offset.x(), offset.y(), offset.z(), speed);
    EXPECT_LT(offset.norm(), 5.0 * kPenetrationBound) << "log " << k << " left the stack";
    EXPECT_LT(offset.head<2>().norm(), 3.0 * kPenetrationBound) << k;
    EXPECT_GT(offset.z(), -3.0 * kPenetrationBound) << "log " << k << " sinks";
    EXPECT_LT(speed, speed_bound) << k;
  }
  // the top log still rests on both bottom logs
  int top_contacts = 0;
  for (const ContactState& c : sim.contacts()) {
    if (c.body_a == 2 || c.body_b == 2) ++top_contacts;
  }
  EXPECT_GE(top_contacts, 2);
  EXPECT_LE(run.last().max_penetration, 2.0 * kPenetrationBound);
  EXPECT_LE(run.max_energy_excess(), 0.0) << "at t = " << run.max_energy_excess_time();
  EXPECT_TRUE(run.finite());
}

TEST(RestingContact, StackOfThreeStaysStacked) { CheckStack(SolverOptions{}.tolerance_rel, 1e-5); }

// With a tight solve the pile is at rest to the bound (speeds < 1e-6 m/s). The log pile is
// neutrally stable (it can roll sideways as a whole at no cost: no rolling resistance), and a
// contact kept in the index set at a 1e-9 m gap (kContactHysteresis) leaves it rolling at
// 9.8e-7 m/s (measured); without the hysteresis 6e-12 m/s.
TEST(RestingContact, StackOfThreeStaysStackedAtRestWithATightSolve) { CheckStack(1e-10, 1e-6); }

}  // namespace
}  // namespace nonsmooth_sim
