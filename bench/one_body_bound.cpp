// A measurement, not a simulator: how fast the Tippe-Top's step could be if it were written for
// its case alone, one body on the static ground, from the core's own pieces (the collision table,
// the contact frame, the Jacobian rows and Delassus blocks, the contact solver, the warm starts of
// simulator.h, the gap correction's lift). What Simulator::Step does besides, and this loop does
// not: the broad phase and the islands, the contact memories' map, the contact report and the
// statistics, the finiteness checks, external wrenches, the implicit gyroscopic passes, the
// levelling of a body on several points, several bodies, restitution, face points.
//
// Its trajectory must equal Simulator's bit for bit (it takes the same steps in the same order of
// operations); the program checks that at the end and fails otherwise. So the ratio of the two
// CPU times is the most a step restructured for this case could gain with the present pieces
// (docs/performance.md, "A step written for one body on the ground").
//
//   one_body_bound [--duration SECONDS] [--rounds N]
//
// Each round runs the bound, then Simulator (thread CPU time of the stepping loop each), and prints
// one JSON line: {"bound_ms", "simulator_ms", "ratio", "identical", ...}; the last line has the
// medians. Exit status 1 if a round's final state differs.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/core/contact/contact_frame.h"
#include "nonsmooth_sim/core/contact/contact_jacobian.h"
#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim {
namespace {

double ThreadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// A contact's memory across steps (simulator.h, ContactMemory): the last three percussions, when
// it was closed, and how its next solve starts.
struct Memory {
  long closed_step = -10;
  long closed_before = -10;
  long closed_before2 = -10;
  Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
  Eigen::Vector4d percussion_before = Eigen::Vector4d::Zero();
  Eigen::Vector4d percussion_before2 = Eigen::Vector4d::Zero();
  Eigen::Vector3d tangent1 = Eigen::Vector3d::UnitX();
  bool converged = false;
  bool sliding = false;  // the last solve projected its friction components
  bool quadratic_served = false;
};

Eigen::Vector4d LinearStart(const Memory& m) { return 2.0 * m.percussion - m.percussion_before; }
Eigen::Vector4d QuadraticStart(const Memory& m) {
  return 3.0 * (m.percussion - m.percussion_before) + m.percussion_before2;
}

// The Tippe-Top (MakeTippeTopScene: the big sphere, the peg sphere, the ground) stepped by (13)-(18)
// with the default options: explicit gyroscopic term, Gauss-Seidel, the sphere set.
class OneBodyOnGround {
 public:
  explicit OneBodyOnGround(const Scene& scene)
      : scene_(scene),
        body_(MakeBodyInertia(scene.bodies[0].mass, scene.bodies[0].inertia)),
        state_(scene.initial_state[0]) {
    for (int k = 0; k < 2; ++k) law_[k] = CombineLaws(scene_.colliders[kTippeTopGround], scene_.colliders[k]);
    problem_.Resize(2);
    lambda_.resize(2);
  }

  [[gnu::noinline]] void Step();
  const BodyState& state() const { return state_; }

 private:
  struct Closed {
    int collider;
    ContactFrame frame;
    ContactJacobian jacobian;
    Eigen::Vector4d lambda;
  };

  // the pose of sphere collider k for the body at (position, rotation)
  Eigen::Isometry3d Pose(int k, const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation) const {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation;
    pose.translation() = rotation * scene_.colliders[static_cast<std::size_t>(k)].pose.translation() + position;
    return pose;
  }
  int CollideWithGround(int k, const Eigen::Isometry3d& pose, double margin, ContactGeometry* out) const {
    return scene_.collision_table.Collide(scene_.colliders[kTippeTopGround].shape, ground_pose_,
                                          scene_.colliders[static_cast<std::size_t>(k)].shape, pose,
                                          margin, out);
  }

  Scene scene_;
  BodyInertia body_;
  BodyState state_;
  ContactLaw law_[2];
  Eigen::Isometry3d ground_pose_ = Eigen::Isometry3d::Identity();
  Memory memory_[2];
  ContactSolver solver_;
  SolverOptions options_;
  SolverStatistics statistics_;
  BlockContactProblem problem_;
  std::vector<Eigen::Vector4d> lambda_;
  long step_ = 0;
  double dt_ = SimulatorOptions{}.time_step;
};

void OneBodyOnGround::Step() {
  const double half_dt = 0.5 * dt_;
  // (13), (14): q_M and the free velocities
  const Eigen::Vector3d position_mid = state_.position + half_dt * state_.linear_velocity;
  const Eigen::Quaterniond orientation_mid =
      AdvanceOrientation(state_.orientation, state_.angular_velocity, half_dt).normalized();
  const Eigen::Matrix3d rotation_mid = orientation_mid.toRotationMatrix();
  const Eigen::Vector3d linear_free = state_.linear_velocity + dt_ * scene_.gravity;
  const Eigen::Vector3d angular_free =
      state_.angular_velocity +
      InverseInertiaTimes(body_, dt_ * GyroscopicTorque(body_, state_.angular_velocity));
  // (12): the closed contacts at q_M, their W and warm starts
  Closed closed[2];
  int n = 0;
  ContactGeometry geometry[kMaxPairContacts];
  for (int k = 0; k < 2; ++k) {
    if (CollideWithGround(k, Pose(k, position_mid, rotation_mid), kContactHysteresis, geometry) <= 0) continue;
    const Memory& m = memory_[k];
    const bool was_closed = m.closed_step == step_ - 1;
    if (geometry[0].gap > (was_closed ? kContactHysteresis : 0.0)) continue;
    Closed& c = closed[n++];
    c.collider = k;
    c.frame = MakeContactFrame(geometry[0].normal, was_closed ? &m.tangent1 : nullptr,
                               Eigen::Vector3d::UnitX());
    c.jacobian.linear = ContactLinearRows(c.frame);
    c.jacobian.side[0].body = 0;
    SetAngularRows(ContactAngularRows(c.frame, geometry[0].point_b, position_mid, rotation_mid),
                   body_, &c.jacobian.side[0]);
  }
  // warm starts: extrapolated for a lone contact, or for two that both slid in the last step
  bool extrapolating = true;
  for (int i = 0; n > 1 && i < n; ++i) {
    const Memory& m = memory_[closed[i].collider];
    extrapolating = extrapolating && m.sliding && m.closed_step == step_ - 1;
  }
  for (int i = 0; i < n; ++i) {
    const Memory& m = memory_[closed[i].collider];
    Eigen::Vector4d& start = closed[i].lambda;
    if (m.closed_step != step_ - 1) {
      start.setZero();
    } else if (extrapolating && m.converged && m.closed_before == step_ - 2) {
      start = m.quadratic_served ? QuadraticStart(m) : LinearStart(m);
    } else {
      start = m.percussion;
    }
  }
  // (16), (17)
  const auto free_velocity = [&](const Closed& c) -> Eigen::Vector4d {
    return c.jacobian.linear * linear_free + c.jacobian.side[0].angular * angular_free;
  };
  if (n == 1) {
    Closed& c = closed[0];
    solver_.SolveOnePrevalidated(OwnDelassusBlock(body_, c.jacobian.side[0]), free_velocity(c),
                                 law_[c.collider], options_, &c.lambda, &statistics_);
  } else if (n == 2) {
    for (int i = 0; i < 2; ++i) {
      problem_.laws[static_cast<std::size_t>(i)] = law_[closed[i].collider];
      problem_.c[static_cast<std::size_t>(i)] = free_velocity(closed[i]);
      problem_.G[static_cast<std::size_t>(3 * i)] = OwnDelassusBlock(body_, closed[i].jacobian.side[0]);
      lambda_[static_cast<std::size_t>(i)] = closed[i].lambda;
    }
    problem_.G[1] = SideDelassusBlock(body_, closed[0].jacobian, closed[0].jacobian.side[0],
                                      closed[1].jacobian, closed[1].jacobian.side[0]);
    problem_.G[2] = problem_.G[1].transpose();
    solver_.SolvePrevalidated(problem_, options_, &lambda_, &statistics_);
    closed[0].lambda = lambda_[0];
    closed[1].lambda = lambda_[1];
  }
  // (18) and the memories
  Eigen::Vector3d linear_contact = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_contact = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Closed& c = closed[i];
    linear_contact += c.jacobian.linear.transpose() * c.lambda;
    angular_contact += c.jacobian.side[0].angular.transpose() * c.lambda;
    Memory& m = memory_[c.collider];
    m.quadratic_served = false;
    if (n == 1 && statistics_.converged && statistics_.iterations <= 2 &&
        m.closed_step == step_ - 1 && m.closed_before == step_ - 2 && m.closed_before2 == step_ - 3) {
      m.quadratic_served = (QuadraticStart(m) - c.lambda).cwiseAbs().maxCoeff() <
                           (LinearStart(m) - c.lambda).cwiseAbs().maxCoeff();
    }
    m.converged = statistics_.converged;
    m.sliding = statistics_.friction_projected[static_cast<std::size_t>(i)] != 0;
    m.tangent1 = c.frame.tangent1;
    m.percussion_before2 = m.percussion_before;
    m.percussion_before = m.percussion;
    m.percussion = c.lambda;
    m.closed_before2 = m.closed_before;
    m.closed_before = m.closed_step;
    m.closed_step = step_;
  }
  // (15), (18): u_E, q_E
  state_.linear_velocity = linear_free + body_.inverse_mass * linear_contact;
  state_.angular_velocity = angular_free + InverseInertiaTimes(body_, angular_contact);
  state_.position = position_mid + half_dt * state_.linear_velocity;
  state_.orientation = AdvanceOrientation(orientation_mid, state_.angular_velocity, half_dt).normalized();
  // the gap correction: the highest end gap of the closed contacts lifts the body to the slop
  if (n > 0) {
    const Eigen::Matrix3d rotation_end = state_.orientation.toRotationMatrix();
    double highest = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    for (int i = 0; i < n; ++i) {
      const int k = closed[i].collider;
      const bool found = CollideWithGround(k, Pose(k, state_.position, rotation_end), 0.0, geometry) > 0;
      const double gap = found ? geometry[0].gap : std::numeric_limits<double>::infinity();
      if (gap > highest) {
        highest = gap;
        normal = found ? geometry[0].normal : closed[i].frame.normal;
      }
    }
    if (-highest > kGapCorrectionSlop) state_.position += (-highest - kGapCorrectionSlop) * normal;
  }
  ++step_;
}

bool SameState(const BodyState& a, const BodyState& b) {
  return a.position == b.position && a.orientation.coeffs() == b.orientation.coeffs() &&
         a.linear_velocity == b.linear_velocity && a.angular_velocity == b.angular_velocity;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int Run(double duration, int rounds) {
  const Scene scene = MakeTippeTopScene();
  const SimulatorOptions options;
  const long steps = std::lround(duration / options.time_step);
  std::vector<double> bound_ms, simulator_ms, ratio;
  bool all_identical = true;
  for (int r = 0; r < rounds; ++r) {
    OneBodyOnGround bound(scene);
    double start = ThreadCpuSeconds();
    for (long i = 0; i < steps; ++i) bound.Step();
    bound_ms.push_back(1e3 * (ThreadCpuSeconds() - start));

    Simulator simulator(scene, options);
    StepStatistics statistics;
    start = ThreadCpuSeconds();
    for (long i = 0; i < steps; ++i) simulator.Step(&statistics);
    simulator_ms.push_back(1e3 * (ThreadCpuSeconds() - start));

    ratio.push_back(simulator_ms.back() / bound_ms.back());
    const bool identical = SameState(bound.state(), simulator.state()[0]);
    all_identical = all_identical && identical;
    const Eigen::Vector3d axis = bound.state().orientation * Eigen::Vector3d::UnitZ();
    std::printf("{\"round\": %d, \"steps\": %ld, \"bound_ms\": %.3f, \"simulator_ms\": %.3f, "
                "\"ratio\": %.3f, \"identical\": %s, \"theta_end\": %.6f}\n",
                r, steps, bound_ms.back(), simulator_ms.back(), ratio.back(),
                identical ? "true" : "false", std::acos(std::clamp(axis.z(), -1.0, 1.0)));
  }
  std::printf("{\"median_bound_ms\": %.3f, \"median_simulator_ms\": %.3f, \"median_ratio\": %.3f, "
              "\"identical\": %s}\n",
              Median(bound_ms), Median(simulator_ms), Median(ratio),
              all_identical ? "true" : "false");
  return all_identical ? 0 : 1;
}

}  // namespace
}  // namespace nonsmooth_sim

int main(int argc, char** argv) {
  double duration = 8.0;
  int rounds = 5;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--duration") == 0 && has_value) {
      duration = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--rounds") == 0 && has_value) {
      rounds = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: one_body_bound [--duration SECONDS] [--rounds N]\n");
      return 2;
    }
  }
  if (!(duration > 0.0 && duration <= 1e4) || rounds < 1 || rounds > 1000) {
    std::fprintf(stderr, "one_body_bound: --duration must be in (0, 1e4] s, --rounds in [1, 1000]\n");
    return 2;
  }
  return nonsmooth_sim::Run(duration, rounds);
}
