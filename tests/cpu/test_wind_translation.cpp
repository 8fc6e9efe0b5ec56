// The wind moves a cloud's density field as a whole (volume/cloud_model.hpp: q = p - wind t),
// which is what lets the viewer drift clouds by translating them, with no new density: the field
// with wind at time t equals the windless field at the same time, sampled wind * t upwind.
#include <gtest/gtest.h>

#include <random>

#include "nimbus/volume/cloud_model.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

TEST(WindTranslation, FieldWithWindIsTheWindlessFieldTranslated) {
  for (const char* name : {"cumulus-mediocris", "cumulus-humilis", "cirrus-fibratus"}) {
    CloudParams windy = cloud_from_json(load_preset(name).at("cloud"), name);
    windy.wind = glm::dvec3(7.0, -3.0, 0.5);
    windy.evolution = 0.01;  // the noise evolves too: the equality must hold at the same time
    CloudParams still = windy;
    still.wind = glm::dvec3(0.0);
    const double t = 137.0;
    const CloudModel a(windy, 20.0, t), b(still, 20.0, t);
    const Aabb box = a.bounds();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int inside = 0;
    for (int i = 0; i < 20000; ++i) {  // cirrus streaks fill under 1 % of their box
      const glm::dvec3 p = box.lo + (box.hi - box.lo) * glm::dvec3(u(rng), u(rng), u(rng));
      const float da = a.density(p), db = b.density(p - windy.wind * t);
      ASSERT_NEAR(da, db, 1e-5f * std::max(1.0f, da)) << name << " at " << p.x << "," << p.y << "," << p.z;
      inside += da > 0.0f;
    }
    EXPECT_GT(inside, 100) << name << ": the samples must reach cloud";
    // And the wind does move it: the unshifted windless field differs.
    int differ = 0;
    for (int i = 0; i < 2500; ++i) {
      const glm::dvec3 p = box.lo + (box.hi - box.lo) * glm::dvec3(u(rng), u(rng), u(rng));
      differ += std::abs(a.density(p) - b.density(p)) > 1e-3f;
    }
    EXPECT_GT(differ, 10) << name;
  }
}

}  // namespace
}  // namespace nimbus::volume
