// The shaders' one light evaluation (shaders/lib/light_eval.glsl compiled as C++, over the
// LightRecord that render::light_record packs) against light.hpp's light_at in double: the
// propagation direction and the irradiance of the sun, a lamp and spots, at hard points (on the
// lamp, inside its minimum distance, on a cone's edges, kilometres away).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "nimbus/render/core/light.hpp"
#include "nimbus/render/core/light_record.hpp"

namespace nimbus::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Float against double: each channel's error relative to the light's unweighted irradiance there
// (a spot's weight near its outer edge is a float cancellation of cosines: tiny absolutely, not
// relatively).
void expect_agrees(const Light& light, const glm::dvec3& x, double rel_tol) {
  SCOPED_TRACE(testing::Message() << "x = (" << x.x << ", " << x.y << ", " << x.z << ")");
  const LightAtPoint ref = light_at(light, x);
  const LightRecordAt got = light_record_at(light_record(light), glm::vec3(x));
  Light unweighted = light;
  unweighted.spot_axis = glm::dvec3(0.0);
  const glm::dvec3 full = light_at(unweighted, x).irradiance_w_m2;
  const double scale = std::max({full.x, full.y, full.z});
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::isfinite(got.irradiance_w_m2[k]));
    EXPECT_NEAR(got.irradiance_w_m2[k], ref.irradiance_w_m2[k], rel_tol * scale + 1e-30) << "channel " << k;
  }
  if (ref.distance_m > 1e-6) {
    const glm::dvec3 propagation = -ref.to_light;
    EXPECT_NEAR(glm::length(glm::dvec3(got.propagation)), 1.0, 1e-6);
    EXPECT_GT(glm::dot(glm::dvec3(got.propagation), propagation), 1.0 - 1e-6);
  }
}

TEST(LightRecord, TheSunIsItsIrradianceEverywhere) {
  const Light sun = sun_light({0.3, 0.8, -0.5}, {2.0, 3.0, 4.0});
  for (const glm::dvec3 x : {glm::dvec3(0.0), glm::dvec3(1e5, -3e4, 2e3), glm::dvec3(-1e-3, 7.0, 1e6)})
    expect_agrees(sun, x, 1e-6);
  const LightRecord r = light_record(sun);
  EXPECT_EQ(r.position.w, float(contract::LIGHT_SUN));
  EXPECT_NEAR(glm::length(glm::vec3(r.position)), 1.0f, 1e-6f);  // normalised on packing
}

TEST(LightRecord, ALampFallsOffAsTheInverseSquareWithItsFloor) {
  Light lamp = point_light({1.0, 2.0, 3.0}, {100.0, 50.0, 25.0});
  lamp.min_distance_m = 0.25;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double r = std::pow(10.0, 4.0 * (u(rng) + 1.0) - 3.0);  // 1 mm to 100 km
    glm::dvec3 dir(u(rng), u(rng), u(rng));
    if (glm::length(dir) < 1e-3) continue;
    expect_agrees(lamp, lamp.position_m + glm::normalize(dir) * r, 1e-5);
  }
  // On the lamp itself and inside its floor: I / r_min^2, finite.
  expect_agrees(lamp, lamp.position_m, 1e-6);
  const LightRecordAt at = light_record_at(light_record(lamp), glm::vec3(lamp.position_m));
  EXPECT_NEAR(at.irradiance_w_m2.x, 100.0 / (0.25 * 0.25), 1e-3);
  EXPECT_EQ(light_record(lamp).position.w, float(contract::LIGHT_LAMP));
}

TEST(LightRecord, ASpotWeighsByItsConeAsSpotWeightDoes) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
  const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(1.0, 0.0, 0.0)));
  for (const auto& [inner, outer] : {std::pair{0.3, 0.5}, std::pair{0.4, 0.4}, std::pair{1.0, kPi}}) {
    SCOPED_TRACE(testing::Message() << "inner " << inner << ", outer " << outer);
    const Light spot = point_light({0.0, 10.0, 0.0}, {80.0, 80.0, 60.0}, axis * 3.0, inner, outer);
    // Angles across the cone, the edges included (a hard cone's edge is where float and double
    // may round to different sides, so it is stepped over by 1e-4 rad).
    for (double angle = 0.0; angle <= kPi; angle += 0.01) {
      if (std::abs(angle - inner) < 1e-4 || std::abs(angle - outer) < 1e-4) continue;
      const glm::dvec3 dir = std::cos(angle) * axis + std::sin(angle) * side;
      const glm::dvec3 x = spot.position_m + 7.0 * dir;
      const double w = spot_weight(spot, dir);
      const LightRecordAt got = light_record_at(light_record(spot), glm::vec3(x));
      EXPECT_NEAR(got.irradiance_w_m2.x, 80.0 / 49.0 * w, 2e-4 * 80.0 / 49.0) << "angle " << angle;
      expect_agrees(spot, x, 2e-4);
    }
  }
}

TEST(LightRecord, NoLightDeliversNothing) {
  const LightRecord none = no_light_record();
  const LightRecordAt at = light_record_at(none, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(at.irradiance_w_m2, glm::vec3(0.0f));
  EXPECT_EQ(at.propagation, glm::vec3(0.0f, -1.0f, 0.0f));
}

TEST(LightRecord, AnInvalidLightIsRefusedNamingTheField) {
  Light lamp = point_light({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  lamp.min_distance_m = 0.0;
  try {
    (void)light_record(lamp);
    FAIL() << "a zero min distance was packed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_distance_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nimbus::render
