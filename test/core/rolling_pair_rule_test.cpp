// The rolling-resistance length μ_r of a contact: the pair rule (CombineLaws: μ_r = min, the
// ground's default neutral), its bounds (ValidateLaw), and which contacts get the rolling
// components (HasRolling: μ > 0, R̄ > 0, μ_r > 0 and a rolling row of the laws table).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/friction_law.h"
#include "nonsmooth_sim/core/scene.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

ContactLaw Law(FrictionSet set, double mu, double rbar, float mu_r) {
  ContactLaw law;
  law.mu = mu;
  law.rbar = rbar;
  law.friction_set = set;
  law.rolling_resistance = mu_r;
  return law;
}

TEST(RollingPairRule, TheSmallerLengthDecidesAndTheGroundIsNeutral) {
  const Collider a = test::SphereCollider("a", 0, Eigen::Vector3d::Zero(), 0.1,
                                          Law(FrictionSet::kRolling, 0.5, 1e-4, 2e-4f));
  const Collider b = test::SphereCollider("b", 1, Eigen::Vector3d::Zero(), 0.1,
                                          Law(FrictionSet::kRolling, 0.5, 1e-4, 5e-5f));
  EXPECT_EQ(CombineLaws(a, b).rolling_resistance, 5e-5f);
  EXPECT_EQ(CombineLaws(b, a).rolling_resistance, 5e-5f);
  // the ground's default law lets the body's μ_r decide, as its μ
  EXPECT_EQ(GroundLaw().rolling_resistance, std::numeric_limits<float>::max());
  EXPECT_EQ(CombineLaws(a, GroundPlane()).rolling_resistance, 2e-4f);
  EXPECT_EQ(CombineLaws(GroundPlane(), a).rolling_resistance, 2e-4f);
  // a body without rolling resistance has none on the ground
  const Collider c = test::SphereCollider("c", 0, Eigen::Vector3d::Zero(), 0.1, ContactLaw{});
  EXPECT_EQ(CombineLaws(c, GroundPlane()).rolling_resistance, 0.0f);
}

TEST(RollingPairRule, TheLengthIsFiniteAndNotNegative) {
  for (float bad : {-1e-4f, std::numeric_limits<float>::quiet_NaN(),
                    std::numeric_limits<float>::infinity()}) {
    try {
      ValidateLaw("law", Law(FrictionSet::kRolling, 0.5, 1e-4, bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("law.rolling_resistance"), std::string::npos) << what;
      EXPECT_NE(what.find("finite, >= 0 [m]"), std::string::npos) << what;
    }
  }
  EXPECT_NO_THROW(ValidateLaw("law", Law(FrictionSet::kRolling, 0.5, 1e-4, 0.0f)));
  EXPECT_NO_THROW(ValidateLaw("law", GroundLaw()));
}

TEST(RollingPairRule, OnlyRollingRowsWithFrictionDrillingAndALengthRoll) {
  EXPECT_TRUE(HasRolling(Law(FrictionSet::kRolling, 0.5, 1e-4, 1e-4f)));
  EXPECT_TRUE(HasRolling(Law(FrictionSet::kRollingDecoupled, 0.5, 1e-4, 1e-4f)));
  EXPECT_EQ(ContactDimensionWithRolling(Law(FrictionSet::kRolling, 0.5, 1e-4, 1e-4f)), 6);
  // no length, no friction, no drilling patch, or a row without rolling: the contact's own
  // dimension
  EXPECT_EQ(ContactDimensionWithRolling(Law(FrictionSet::kRolling, 0.5, 1e-4, 0.0f)), 4);
  EXPECT_EQ(ContactDimensionWithRolling(Law(FrictionSet::kRolling, 0.0, 1e-4, 1e-4f)), 1);
  EXPECT_EQ(ContactDimensionWithRolling(Law(FrictionSet::kRolling, 0.5, 0.0, 1e-4f)), 3);
  for (FrictionSet set : kAllFrictionSets) {
    const bool rolling = LawOf(set).rolling != RollingKind::kNone;
    EXPECT_EQ(HasRolling(Law(set, 0.5, 1e-4, 1e-4f)), rolling) << FrictionSetName(set);
  }
  // μ_r lives in the struct's padding
  EXPECT_EQ(sizeof(ContactLaw), 32u);
}

}  // namespace
}  // namespace nonsmooth_sim
