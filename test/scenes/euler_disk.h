// Euler's disk as the scene tests model it (urdf/euler_disk.urdf; docs/scenes.md section 1): the
// disc's dimensions read back from the loaded scene and its steady rolling with the centre of mass
// S at rest, (D1) and (D2) of docs/scenes.md (derived at the top of euler_disk_test.cpp).
#ifndef NONSMOOTH_SIM_TEST_SCENES_EULER_DISK_H_
#define NONSMOOTH_SIM_TEST_SCENES_EULER_DISK_H_

#include <cmath>

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim::scene_test {

inline constexpr double kG = 9.81;

struct Disc {
  double a = 0.0;  // radius [m]
  double h = 0.0;  // thickness [m]
  double m = 0.0;  // [kg]
  double A = 0.0;  // about a diameter through S [kg m²]
  double C = 0.0;  // about the axis [kg m²]
};

// The geometry as modelled: read back from the loaded scene.
inline Disc DiscOf(const Scene& scene) {
  const Collider& c = scene.colliders[static_cast<std::size_t>(FindCollider(scene, "disk"))];
  Disc d;
  d.a = c.shape.radius;
  d.h = 2.0 * c.shape.half_length;
  d.m = scene.bodies[0].mass;
  d.A = scene.bodies[0].inertia(0, 0);
  d.C = scene.bodies[0].inertia(2, 2);
  return d;
}

// (D1) [rad/s]
inline double SteadyPrecessionRate(const Disc& d, double alpha) {
  const double c = std::cos(alpha);
  const double s = std::sin(alpha);
  return std::sqrt(d.m * kG * (d.a * c - 0.5 * d.h * s) /
                   (s * (d.A * c - d.C * d.h / (2.0 * d.a) * s)));
}

// Steady rolling with S at rest at (0, 0, z_S): e3 tilted by α about the world x axis, the lowest
// rim point touching, (D2) in the body axes: ω_K = (0, Ω sin α, Ω (h/2a) sin α).
inline BodyState SteadyRollingState(const Disc& d, double alpha) {
  BodyState s;
  s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  s.position = Eigen::Vector3d(0.0, 0.0, 0.5 * d.h * std::cos(alpha) + d.a * std::sin(alpha));
  const double omega = SteadyPrecessionRate(d, alpha);
  s.angular_velocity = Eigen::Vector3d(0.0, omega * std::sin(alpha),
                                       omega * d.h / (2.0 * d.a) * std::sin(alpha));
  return s;
}

}  // namespace nonsmooth_sim::scene_test

#endif  // NONSMOOTH_SIM_TEST_SCENES_EULER_DISK_H_
