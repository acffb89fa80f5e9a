// Every shipped start (config/<scene>.yaml on urdf/<scene>.urdf) is where its YAML comment says:
// no collider penetrates the ground or another body, and the bodies said to rest on the floor
// touch it (gap 0 to round-off); the die starts in the air. The heights were derived by hand in
// the YAML comments; this recomputes them with the pair functions (docs/scenes.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "scene_test_support.h"

namespace nonsmooth_sim {
namespace {

using scene_test::LoadShippedScene;

// Smallest gap between any two colliders that can touch (different bodies, or a body and the
// world), at the scene's start [m].
double SmallestGap(const Scene& scene, const std::string& only_with = "") {
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    for (std::size_t j = i + 1; j < scene.colliders.size(); ++j) {
      const Collider& a = scene.colliders[i];
      const Collider& b = scene.colliders[j];
      if (a.body == b.body) continue;
      if (!only_with.empty() && a.name != only_with && b.name != only_with) continue;
      const auto pose = [&scene](const Collider& c) {
        if (c.body == kWorld) return c.pose;
        return Eigen::Isometry3d(BodyPose(scene.initial_state[static_cast<std::size_t>(c.body)]) *
                                 c.pose);
      };
      ContactGeometry g[kMaxPairContacts];
      const int n = scene.collision_table.Collide(a.shape, pose(a), b.shape, pose(b), 1.0, g);
      for (int k = 0; k < n; ++k) smallest = std::min(smallest, g[k].gap);
    }
  }
  return smallest;
}

TEST(ShippedStarts, RestingScenesTouchTheGroundWithoutPenetrating) {
  for (const char* name : {"euler_disk", "rattleback", "spinning_egg", "classic_top",
                           "tippe_top_duel", "coin"}) {
    const Scene scene = LoadShippedScene(name);
    const double ground = SmallestGap(scene, "ground");
    const double any = SmallestGap(scene);
    std::printf("%-15s smallest gap to the ground %.2e m, between any two %.2e m\n", name, ground,
                any);
    EXPECT_NEAR(ground, 0.0, 1e-15) << name;
    EXPECT_GE(any, -1e-15) << name;
  }
}

TEST(ShippedStarts, TheDieStartsInTheAir) {
  const Scene scene = LoadShippedScene("die");
  // config/die.yaml: the lowest corner 0.011863 m below S at z_S = 0.04 m
  EXPECT_NEAR(SmallestGap(scene, "ground"), 0.04 - 0.011863434273713697, 1e-12);
}

TEST(ShippedStarts, TheDuelsBigSpheresStartTenMillimetresApart) {
  const Scene scene = LoadShippedScene("tippe_top_duel");
  EXPECT_NEAR(SmallestGap(scene, "top1_big_sphere"), 0.0, 1e-15);  // on the ground
  const int a = FindCollider(scene, "top1_big_sphere");
  const int b = FindCollider(scene, "top2_big_sphere");
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  const Eigen::Isometry3d pa = BodyPose(scene.initial_state[0]) * scene.colliders[a].pose;
  const Eigen::Isometry3d pb = BodyPose(scene.initial_state[1]) * scene.colliders[b].pose;
  ContactGeometry g[kMaxPairContacts];
  ASSERT_EQ(scene.collision_table.Collide(scene.colliders[a].shape, pa, scene.colliders[b].shape,
                                          pb, 1.0, g),
            1);
  EXPECT_NEAR(g[0].gap, 0.010, 1e-15);
}

}  // namespace
}  // namespace nonsmooth_sim
