// Tests of shape.h: names, validation messages, bounding radii (never exceeded by a point of the
// shape, attained by one), and volumes and unit inertias against closed forms and Monte-Carlo
// integration of the solids' definitions (the table at the top of shape.h), fixed seed.
#include "nonsmooth_sim/core/shape.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/constants.h"

namespace nonsmooth_sim {
namespace {

using collision_test::kSeed;

const std::vector<Shape>& SolidShapes() {
  static const std::vector<Shape> shapes = {
      Shape::Sphere(0.3),         Shape::Capsule(0.2, 0.35),   Shape::Ellipsoid({0.3, 0.15, 0.45}),
      Shape::Cylinder(0.25, 0.4), Shape::Box({0.1, 0.3, 0.2}),
  };
  return shapes;
}

// Membership of a point y (shape frame) in the solid, straight from shape.h's table.
bool Contains(const Shape& s, const Eigen::Vector3d& y) {
  switch (s.type) {
    case ShapeType::kPlane: return y.z() <= 0.0;
    case ShapeType::kSphere: return y.norm() <= s.radius;
    case ShapeType::kCapsule: {
      const double z = std::clamp(y.z(), -s.half_length, s.half_length);
      return (y - Eigen::Vector3d(0, 0, z)).norm() <= s.radius;
    }
    case ShapeType::kEllipsoid: return y.cwiseQuotient(s.half_extents).squaredNorm() <= 1.0;
    case ShapeType::kCylinder:
      return y.x() * y.x() + y.y() * y.y() <= s.radius * s.radius &&
             std::abs(y.z()) <= s.half_length;
    case ShapeType::kBox: return (y.cwiseAbs() - s.half_extents).maxCoeff() <= 0.0;
    case ShapeType::kConvexHull:  // tested with its pair (collision_plane_hull_test.cpp)
    case ShapeType::kRevolution: break;  // and revolution_profile_test.cpp
  }
  return false;
}

// Half-extents of the shape frame's axis-aligned bounding box.
Eigen::Vector3d BoxOf(const Shape& s) {
  switch (s.type) {
    case ShapeType::kCapsule: return {s.radius, s.radius, s.radius + s.half_length};
    case ShapeType::kCylinder: return {s.radius, s.radius, s.half_length};
    case ShapeType::kEllipsoid:
    case ShapeType::kBox: return s.half_extents;
    default: return Eigen::Vector3d::Constant(s.radius);
  }
}

TEST(ShapeNames, RoundTripAndUnknown) {
  for (int i = 0; i < kShapeTypeCount; ++i) {
    const auto type = static_cast<ShapeType>(i);
    const auto back = ShapeTypeFromName(ShapeTypeName(type));
    ASSERT_TRUE(back.has_value()) << ShapeTypeName(type);
    EXPECT_EQ(*back, type);
  }
  EXPECT_EQ(ShapeTypeName(ShapeType::kEllipsoid), "ellipsoid");
  EXPECT_FALSE(ShapeTypeFromName("cone").has_value());
  EXPECT_FALSE(ShapeTypeFromName("Sphere").has_value());
}

TEST(ShapeFactories, SetTypeAndParameters) {
  EXPECT_EQ(Shape::Plane().type, ShapeType::kPlane);
  const Shape capsule = Shape::Capsule(0.1, 0.2);
  EXPECT_EQ(capsule.type, ShapeType::kCapsule);
  EXPECT_EQ(capsule.radius, 0.1);
  EXPECT_EQ(capsule.half_length, 0.2);
  const Shape box = Shape::Box({1, 2, 3});
  EXPECT_EQ(box.type, ShapeType::kBox);
  EXPECT_EQ(box.half_extents, Eigen::Vector3d(1, 2, 3));
}

std::string ValidationMessage(const Shape& shape) {
  try {
    ValidateShape(shape, "scene.colliders[2].shape");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateShape, NamesWhereAndTheBadParameter) {
  EXPECT_EQ(ValidationMessage(Shape::Sphere(-1)),
            "scene.colliders[2].shape: radius = -1: must be finite, > 0 [m]");
  EXPECT_EQ(ValidationMessage(Shape::Capsule(0.1, -0.5)),
            "scene.colliders[2].shape: half_length = -0.5: must be finite, >= 0 [m]");
  EXPECT_EQ(ValidationMessage(Shape::Cylinder(0.1, 0.0)),
            "scene.colliders[2].shape: half_length = 0: must be finite, > 0 [m]");
  EXPECT_EQ(ValidationMessage(Shape::Box({1, 0, 1})),
            "scene.colliders[2].shape: half_extents.y = 0: must be finite, > 0 [m]");
  EXPECT_EQ(ValidationMessage(Shape::Ellipsoid({1, 1, NAN})),
            "scene.colliders[2].shape: semi_axes.z = nan: must be finite, > 0 [m]");
  EXPECT_EQ(ValidationMessage(Shape::Sphere(INFINITY)),
            "scene.colliders[2].shape: radius = inf: must be finite, > 0 [m]");
}

TEST(ValidateShape, AcceptsValidShapes) {
  for (const Shape& shape : SolidShapes()) EXPECT_NO_THROW(ValidateShape(shape, "s"));
  EXPECT_NO_THROW(ValidateShape(Shape::Plane(), "s"));
  EXPECT_NO_THROW(ValidateShape(Shape::Capsule(0.1, 0.0), "s"));  // a capsule may be a sphere
}

// No point of the shape lies beyond BoundingRadius, and the extreme support point reaches it.
TEST(BoundingRadius, HoldsTheShapeAndIsAttained) {
  std::mt19937 rng(kSeed);
  for (const Shape& shape : SolidShapes()) {
    const double bound = BoundingRadius(shape);
    double farthest = 0.0;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Vector3d d(collision_test::Uniform(rng, -1, 1),
                              collision_test::Uniform(rng, -1, 1),
                              collision_test::Uniform(rng, -1, 1));
      farthest = std::max(farthest,
                          collision_test::Support(shape, Eigen::Isometry3d::Identity(), d).norm());
    }
    // the farthest points: the corner, the rim, the poles, the longest semi-axis
    const Eigen::Vector3d corner = BoxOf(shape);
    double attained = shape.type == ShapeType::kBox ? corner.norm()
                      : shape.type == ShapeType::kCylinder
                          ? std::hypot(shape.radius, shape.half_length)
                          : corner.maxCoeff();
    EXPECT_LE(farthest, bound * (1 + 1e-12)) << ShapeTypeName(shape.type);
    EXPECT_NEAR(attained, bound, 1e-15) << ShapeTypeName(shape.type);
  }
  EXPECT_TRUE(std::isinf(BoundingRadius(Shape::Plane())));
}

TEST(ShapeVolume, ClosedForms) {
  EXPECT_NEAR(ShapeVolume(Shape::Sphere(2.0)), 32.0 * kPi / 3.0, 1e-12);
  EXPECT_NEAR(ShapeVolume(Shape::Box({1, 2, 3})), 48.0, 1e-12);
  EXPECT_NEAR(ShapeVolume(Shape::Cylinder(1.0, 0.5)), kPi, 1e-12);
  // a capsule of half_length 0 is its sphere; an ellipsoid of equal axes is the sphere
  EXPECT_NEAR(ShapeVolume(Shape::Capsule(0.3, 0.0)), ShapeVolume(Shape::Sphere(0.3)), 1e-15);
  EXPECT_NEAR(ShapeVolume(Shape::Ellipsoid({0.3, 0.3, 0.3})), ShapeVolume(Shape::Sphere(0.3)),
              1e-15);
  EXPECT_THROW(ShapeVolume(Shape::Plane()), std::invalid_argument);
  EXPECT_THROW(ShapeUnitInertia(Shape::Plane()), std::invalid_argument);
}

TEST(ShapeUnitInertia, ClosedFormsAndLimits) {
  // solid sphere: (2/5) m r²
  const double m = ShapeVolume(Shape::Sphere(0.5));
  EXPECT_TRUE(ShapeUnitInertia(Shape::Sphere(0.5))
                  .isApprox(Eigen::Matrix3d::Identity() * 0.4 * m * 0.25, 1e-14));
  // capsule of half_length 0 = sphere; ellipsoid of equal axes = sphere
  EXPECT_TRUE(ShapeUnitInertia(Shape::Capsule(0.5, 0.0))
                  .isApprox(ShapeUnitInertia(Shape::Sphere(0.5)), 1e-14));
  EXPECT_TRUE(ShapeUnitInertia(Shape::Ellipsoid({0.5, 0.5, 0.5}))
                  .isApprox(ShapeUnitInertia(Shape::Sphere(0.5)), 1e-14));
  // a cube of side 2: m (b² + c²)/3 = 8·2/3
  EXPECT_TRUE(ShapeUnitInertia(Shape::Box({1, 1, 1}))
                  .isApprox(Eigen::Matrix3d::Identity() * 16.0 / 3.0, 1e-14));
  // a long capsule tends to its cylinder plus point masses at the ends: I_xx/(m l²) → 1/3 as l/r →
  // ∞
  const Shape rod = Shape::Capsule(1e-3, 1.0);
  EXPECT_NEAR(ShapeUnitInertia(rod)(0, 0) / (ShapeVolume(rod) * 1.0), 1.0 / 3.0, 2e-3);
}

// Monte-Carlo over the bounding box, N samples: each estimate is a mean of N i.i.d. terms, and
// is checked to within 5 of its own standard errors (σ/√N, σ from the samples); with a fixed
// seed the outcome is reproducible. N = 400 000 gives σ/√N ≈ 0.1 % of the volume; a wrong
// closed form (a missing hemisphere term, l² for (2l)²) is off by ≥ 2 % and fails.
TEST(ShapeVolumeAndInertia, MatchMonteCarloIntegration) {
  constexpr int kSamples = 400000;
  constexpr double kSigmas = 5.0;
  std::mt19937 rng(kSeed);
  for (const Shape& shape : SolidShapes()) {
    const Eigen::Vector3d e = BoxOf(shape);
    const double box_volume = 8.0 * e.prod();
    // running sums of the integrands f = V_box·[y ∈ shape]·g(y) for g = 1, I_xx, I_yy, I_zz, I_xy
    Eigen::Matrix<double, 5, 1> sum = Eigen::Matrix<double, 5, 1>::Zero();
    Eigen::Matrix<double, 5, 1> sum_sq = Eigen::Matrix<double, 5, 1>::Zero();
    for (int i = 0; i < kSamples; ++i) {
      const Eigen::Vector3d y(collision_test::Uniform(rng, -e.x(), e.x()),
                              collision_test::Uniform(rng, -e.y(), e.y()),
                              collision_test::Uniform(rng, -e.z(), e.z()));
      if (!Contains(shape, y)) continue;
      Eigen::Matrix<double, 5, 1> f;
      f << 1.0, y.y() * y.y() + y.z() * y.z(), y.x() * y.x() + y.z() * y.z(),
          y.x() * y.x() + y.y() * y.y(), -y.x() * y.y();
      f *= box_volume;
      sum += f;
      sum_sq += f.cwiseAbs2();
    }
    const Eigen::Matrix<double, 5, 1> mean = sum / kSamples;
    const Eigen::Matrix<double, 5, 1> standard_error =
        ((sum_sq / kSamples - mean.cwiseAbs2()).cwiseMax(0.0) / kSamples).cwiseSqrt();
    const Eigen::Matrix3d inertia = ShapeUnitInertia(shape);
    const Eigen::Matrix<double, 5, 1> exact(ShapeVolume(shape), inertia(0, 0), inertia(1, 1),
                                            inertia(2, 2), inertia(0, 1));
    const char* names[5] = {"volume", "I_xx", "I_yy", "I_zz", "I_xy"};
    for (int k = 0; k < 5; ++k) {
      // (+ round-off of the sum: the box fills its bounding box, its volume has no variance)
      EXPECT_NEAR(exact[k], mean[k], kSigmas * standard_error[k] + 1e-9 * std::abs(exact[k]))
          << ShapeTypeName(shape.type) << " " << names[k];
    }
    // diagonal in the shape frame (the solids are symmetric about its planes)
    EXPECT_EQ(inertia(0, 1), 0.0);
    EXPECT_EQ(inertia(0, 2), 0.0);
    EXPECT_EQ(inertia(1, 2), 0.0);
  }
}

}  // namespace
}  // namespace nonsmooth_sim
