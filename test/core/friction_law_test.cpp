// The laws table (friction_law.h): every row says of its law what the solver relies on, checked
// against the prox functions themselves (force_sets.h) and the sets they project onto.
#include "nonsmooth_sim/core/friction_law.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "nonsmooth_sim/core/transformation.h"

namespace nonsmooth_sim {
namespace {

constexpr std::uint64_t kSeed = 20261206;
constexpr int kSamples = 2000;

bool SameBits(const Prox3& a, const Prox3& b) {
  return a.region == b.region && a.point.x() == b.point.x() && a.point.y() == b.point.y() &&
         a.point.z() == b.point.z();
}

// A point around a set of the given radius: each component in [-2, 2]·radius (τ scaled by rbar).
Eigen::Vector3d RandomPoint(std::mt19937_64& rng, double radius, double rbar) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  return Eigen::Vector3d(u(rng) * radius, u(rng) * radius, u(rng) * rbar * radius);
}

TEST(FrictionLaws, NamesRoundTripAndUnknownNamesAreNone) {
  for (FrictionSet set : kAllFrictionSets) {
    EXPECT_TRUE(IsFrictionSet(set));
    EXPECT_EQ(LawOf(set).set, set);
    EXPECT_EQ(FrictionSetFromName(FrictionSetName(set)), set) << FrictionSetName(set);
  }
  for (const char* name : {"", "unknown", "Sphere", "sphere ", "exact_unmapped"}) {
    EXPECT_FALSE(FrictionSetFromName(name).has_value()) << '"' << name << '"';
  }
  EXPECT_FALSE(IsFrictionSet(static_cast<FrictionSet>(kFrictionLaws.size())));
  EXPECT_FALSE(IsFrictionSet(static_cast<FrictionSet>(-1)));
  EXPECT_EQ(FrictionSetNameList(),
            "coulomb, cylinder, ellipsoid, sphere, exact, rolling, rolling_decoupled");
}

TEST(FrictionLaws, BitMasksAgreeWithTheRows) {
  for (FrictionSet set : kAllFrictionSets) {
    const FrictionLaw& law = LawOf(set);
    const std::string what(law.name);
    EXPECT_EQ((LawIs<&FrictionLaw::drilling, true>(set)), law.drilling) << what;
    EXPECT_EQ((LawIs<&FrictionLaw::drilling, false>(set)), !law.drilling) << what;
    EXPECT_EQ((LawIs<&FrictionLaw::coordinates, LawCoordinates::kOriginal>(set)),
              law.coordinates == LawCoordinates::kOriginal) << what;
    EXPECT_EQ((LawIs<&FrictionLaw::coordinates, LawCoordinates::kMapped>(set)),
              law.coordinates == LawCoordinates::kMapped) << what;
    EXPECT_EQ((LawIs<&FrictionLaw::coordinates, LawCoordinates::kMappedByOption>(set)),
              law.coordinates == LawCoordinates::kMappedByOption) << what;
    EXPECT_EQ((LawIs<&FrictionLaw::warm_start, WarmStartKind::kPercussion>(set)),
              law.warm_start == WarmStartKind::kPercussion) << what;
    EXPECT_EQ((LawIs<&FrictionLaw::warm_start, WarmStartKind::kPercussionAndRimHint>(set)),
              law.warm_start == WarmStartKind::kPercussionAndRimHint) << what;
  }
}

// The dispatch reaches each row's prox, and each row's prox is the projection its set names.
TEST(FrictionLaws, DispatchCallsTheRowsProxWhichIsTheSetsProjection) {
  std::mt19937_64 rng(kSeed);
  const double rbar = 2.5e-3;
  for (int k = 0; k < kSamples; ++k) {
    const double radius = std::ldexp(1.0, k % 20 - 10);
    const Eigen::Vector3d z = RandomPoint(rng, radius, rbar);
    for (FrictionSet set : kAllFrictionSets) {
      double hint_dispatched = std::numeric_limits<double>::quiet_NaN();
      double hint_row = hint_dispatched;
      const Prox3 dispatched = ProxFrictionLaw(set, z, radius, rbar, &hint_dispatched);
      const Prox3 row = LawOf(set).prox(z, radius, rbar, &hint_row);
      ASSERT_TRUE(SameBits(dispatched, row)) << FrictionSetName(set) << " z = " << z.transpose();
    }
    const auto prox = [&](FrictionSet set) {
      double hint = std::numeric_limits<double>::quiet_NaN();
      return LawOf(set).prox(z, radius, rbar, &hint);
    };
    ASSERT_TRUE(SameBits(prox(FrictionSet::kSphere), ProxBall(z, radius)));
    ASSERT_TRUE(SameBits(prox(FrictionSet::kCylinder), ProxCylinder(z, radius, rbar)));
    ASSERT_TRUE(SameBits(prox(FrictionSet::kEllipsoid), ProxEllipsoid(z, radius, rbar)));
    // the warm-started overload agrees with the plain one to a few ulps (force_sets.h)
    const Prox3 exact = prox(FrictionSet::kExact);
    const Prox3 plain = ProxCoulombContensou(z, radius, rbar);
    ASSERT_EQ(exact.region, plain.region);
    ASSERT_LE((exact.point - plain.point).cwiseAbs().maxCoeff(),
              1e-13 * radius * (1.0 + 1.0 / rbar));
    // coulomb: the planar disk, no drilling percussion
    const Prox3 coulomb = prox(FrictionSet::kCoulomb);
    const Prox2 disk = ProxDisk(z.head<2>(), radius);
    ASSERT_EQ(coulomb.region, disk.region);
    ASSERT_EQ(coulomb.point, Eigen::Vector3d(disk.point.x(), disk.point.y(), 0.0));
  }
}

TEST(FrictionLaws, DrillingDecidesTheDimension) {
  for (FrictionSet set : kAllFrictionSets) {
    ContactLaw law;
    law.friction_set = set;
    law.mu = 0.3;
    law.rbar = 1e-3;
    EXPECT_EQ(ContactDimension(law), LawOf(set).drilling ? 4 : 3) << FrictionSetName(set);
    law.rbar = 0.0;
    EXPECT_EQ(ContactDimension(law), 3) << FrictionSetName(set);
    law.mu = 0.0;
    law.rbar = 1e-3;
    EXPECT_EQ(ContactDimension(law), 1) << FrictionSetName(set);
  }
}

// A ball metric D says the set is {||D⁻¹x|| ≤ radius} (the direct solve, ball_contact_solve.h,
// solves exactly that set); kNone rows are not such a ball.
TEST(FrictionLaws, BallMetricIsTheSet) {
  std::mt19937_64 rng(kSeed + 1);
  const double rbar = 0.4;  // the set's R̄ (set_rbar): 1 where mapped, the law's R̄ otherwise
  const double radius = 1.5;
  for (FrictionSet set : kAllFrictionSets) {
    const FrictionLaw& law = LawOf(set);
    if (law.ball_metric == BallMetric::kNone) continue;
    const Eigen::Vector3d d(1.0, 1.0,
                            law.ball_metric == BallMetric::kDrillingRadius ? rbar : 1.0);
    int inside = 0;
    int outside = 0;
    for (int k = 0; k < kSamples; ++k) {
      Eigen::Vector3d x = RandomPoint(rng, radius, d.z());
      if (!law.drilling) x.z() = 0.0;  // the disk lies in the plane Λ_τ = 0
      const double norm = x.cwiseQuotient(d).norm();
      if (std::abs(norm - radius) < 1e-9 * radius) continue;  // on the boundary: either answer
      double hint = std::numeric_limits<double>::quiet_NaN();
      const Prox3 p = law.prox(x, radius, rbar, &hint);
      const bool in_set = p.region == ProxRegion::kInterior;
      ASSERT_EQ(in_set, norm < radius) << law.name << " x = " << x.transpose();
      (in_set ? inside : outside) += 1;
    }
    EXPECT_GT(inside, kSamples / 20) << law.name;
    EXPECT_GT(outside, kSamples / 20) << law.name;
  }
  // C_F's corner and B_F's boundary point at u = 1 lie off every ball {||D⁻¹x|| = radius} of the
  // two metrics (for the mapped sets, R̄ = 1, both metrics are I)
  const Eigen::Vector3d corner(0.9 * radius, 0.0, 0.9 * radius);
  double hint = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(LawOf(FrictionSet::kCylinder).prox(corner, radius, 1.0, &hint).region,
            ProxRegion::kInterior);
  EXPECT_GT(corner.norm(), radius);
  const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(1.0, radius, 1.0);
  EXPECT_GT(std::abs(std::hypot(b.b_t, b.b_tau) - radius), 1e-3 * radius);
}

// Only a law whose warm start includes the rim hint reads or writes it.
TEST(FrictionLaws, OnlyRimHintLawsWriteTheHint) {
  const double radius = 1.0;
  const double rbar = 1.0;
  // sliding far outside along T, a little drilling: B_F's foot point on its branch u > 1
  const Eigen::Vector3d z(3.0, 0.5, 0.05);
  for (FrictionSet set : kAllFrictionSets) {
    double hint = std::numeric_limits<double>::quiet_NaN();
    LawOf(set).prox(z, radius, rbar, &hint);
    if (LawOf(set).warm_start == WarmStartKind::kPercussionAndRimHint) {
      EXPECT_TRUE(std::isfinite(hint)) << FrictionSetName(set);
    } else {
      EXPECT_TRUE(std::isnan(hint)) << FrictionSetName(set);
      // and it is not read either: the null hint of a law without one is safe
      const Prox3 without = LawOf(set).prox(z, radius, rbar, nullptr);
      EXPECT_EQ(without.region, ProxRegion::kBoundary) << FrictionSetName(set);
    }
  }
}

TEST(FrictionLaws, CoordinatesDecideTheMap) {
  const double rbar = 3e-4;
  const Eigen::Vector4d mapped(1.0, 1.0, 1.0, rbar);
  for (FrictionSet set : kAllFrictionSets) {
    ContactLaw law;
    law.friction_set = set;
    law.mu = 0.3;
    law.rbar = rbar;
    const LawCoordinates c = LawOf(set).coordinates;
    const bool drilling = LawOf(set).drilling;
    for (bool option : {false, true}) {
      const bool is_mapped = drilling && (c == LawCoordinates::kMapped ||
                                          (c == LawCoordinates::kMappedByOption && option));
      EXPECT_EQ(ContactMapDiagonal(law, option),
                is_mapped ? mapped : Eigen::Vector4d(Eigen::Vector4d::Ones()))
          << FrictionSetName(set) << " map_drilling_sets = " << option;
    }
  }
}

// The rows with a rolling set have their 5-D prox, the others none; at μ_r = 0 (no rolling
// components) a rolling row is S_F, the sphere row, and its 5-D set restricted to zero rolling
// torque is S_F again (coupled) or S_F beside a disk (decoupled).
TEST(FrictionLaws, RollingRowsAreTheSphereWithoutRolling) {
  std::mt19937_64 rng(kSeed + 2);
  int rolling_rows = 0;
  for (FrictionSet set : kAllFrictionSets) {
    const FrictionLaw& law = LawOf(set);
    EXPECT_EQ(law.rolling == RollingKind::kNone, law.prox5 == nullptr) << law.name;
    if (law.rolling == RollingKind::kNone) continue;
    ++rolling_rows;
    EXPECT_TRUE(law.drilling) << law.name;
    EXPECT_EQ(law.coordinates, LawCoordinates::kMapped) << law.name;
    for (int k = 0; k < kSamples; ++k) {
      const double radius = std::ldexp(1.0, k % 20 - 10);
      const Eigen::Vector3d z = RandomPoint(rng, radius, 1.0);
      ASSERT_TRUE(SameBits(law.prox(z, radius, 1.0, nullptr), ProxBall(z, radius))) << law.name;
      Vector5d z5;
      z5 << z, 0.0, 0.0;
      const Prox5 p5 = law.prox5(z5, radius);
      const Prox3 p3 = ProxBall(z, radius);
      // the same radial scaling; the 5-D norm sums in another order (an ulp or two)
      ASSERT_LE((p5.point.head<3>() - p3.point).norm(), 1e-15 * radius) << law.name;
      ASSERT_EQ(p5.point.tail<2>(), Eigen::Vector2d::Zero()) << law.name;
      ASSERT_EQ(p5.region, p3.region) << law.name;
    }
  }
  EXPECT_EQ(rolling_rows, 2);
  EXPECT_EQ(LawOf(FrictionSet::kRolling).prox5, &ProxRollingBall);
  EXPECT_EQ(LawOf(FrictionSet::kRollingDecoupled).prox5, &ProxRollingDecoupled);
}

}  // namespace
}  // namespace nonsmooth_sim
