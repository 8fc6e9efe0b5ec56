// The one set-up of the sun, its colour and its ambient light (render/scene/sun_setup.hpp), which
// `nimbus render --sun`, the viewer's clock and FrameRenderer::set_sun all call.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/scene/sun_setup.hpp"

namespace nr = nimbus::render;

namespace {

void expect_vec_eq(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
}

const glm::dvec3 kLow{0.9, 0.08, -0.3};  // about 5 degrees up: a low, reddened sun

}  // namespace

TEST(SunSetup, UnderThePhysicalSkyTheDaylightGivesTheSunTheSkyAndTheAmbient) {
  const nr::Scene sky = nr::make_scene("sky");
  ASSERT_TRUE(sky.sky && sky.sky->atmosphere);
  const nr::SunSetup s = nr::set_up_sun(&sky, kLow, nr::SunColour::Scene);
  const nr::Daylight d = nr::daylight(kLow, sky.sky->atmosphere->view.altitude_m);
  EXPECT_EQ(s.sun.kind, nr::LightKind::Sun);
  expect_vec_eq(s.sun.direction_to_sun, kLow);  // as given, as the metadata echoes it
  expect_vec_eq(s.sun.irradiance_w_m2, d.cloud_sun_irradiance_w_m2);
  ASSERT_TRUE(s.sky && s.sky->atmosphere);
  ASSERT_TRUE(s.ambient_w_sr_m2);
  expect_vec_eq(*s.ambient_w_sr_m2, nr::sky_mean_radiance(*s.sky));
  // The viewer's clock asks for the daylight everywhere: under the physical sky it is the same sun.
  const nr::SunSetup v = nr::set_up_sun(&sky, kLow, nr::SunColour::Daylight);
  expect_vec_eq(v.sun.irradiance_w_m2, s.sun.irradiance_w_m2);
  expect_vec_eq(*v.ambient_w_sr_m2, *s.ambient_w_sr_m2);
}

TEST(SunSetup, ALowSunIsRedderAndDimmerThanAHighOne) {
  const nr::Scene sky = nr::make_scene("sky");
  const glm::dvec3 low = nr::set_up_sun(&sky, kLow, nr::SunColour::Scene).sun.irradiance_w_m2;
  const glm::dvec3 high = nr::set_up_sun(&sky, {0.2, 1.0, -0.1}, nr::SunColour::Scene).sun.irradiance_w_m2;
  EXPECT_GT(low.r / low.b, 1.2 * high.r / high.b);
  EXPECT_LT(low.g, high.g);
}

TEST(SunSetup, AScenesOwnSunMovesAndKeepsItsIrradianceUnlessTheDaylightIsAskedFor) {
  const nr::Scene col = nr::make_scene("colonnade-sun");
  ASSERT_TRUE(col.sun);
  ASSERT_FALSE(col.sky && col.sky->atmosphere);
  const glm::dvec3 to_sun{0.3, 0.6, 0.2};
  const nr::SunSetup s = nr::set_up_sun(&col, to_sun, nr::SunColour::Scene);
  expect_vec_eq(s.sun.direction_to_sun, to_sun);
  expect_vec_eq(s.sun.irradiance_w_m2, col.sun->irradiance_w_m2);
  EXPECT_FALSE(s.sky);  // its gradient sky stays
  EXPECT_EQ(s.ambient_w_sr_m2.has_value(), col.sky.has_value());
  if (col.sky) expect_vec_eq(*s.ambient_w_sr_m2, nr::sky_mean_radiance(*col.sky));

  const nr::SunSetup d = nr::set_up_sun(&col, to_sun, nr::SunColour::Daylight);
  const nr::Daylight day = nr::daylight(to_sun);
  expect_vec_eq(d.sun.irradiance_w_m2, day.cloud_sun_irradiance_w_m2);
  EXPECT_FALSE(d.sky);  // no physical sky to replace
  expect_vec_eq(*d.ambient_w_sr_m2, day.ambient_w_sr_m2);
}

TEST(SunSetup, CloudsAloneTakeTheDefaultSunOrTheDaylight) {
  const nr::SunSetup s = nr::set_up_sun(nullptr, {0.0, 2.0, 0.0}, nr::SunColour::Scene);
  expect_vec_eq(s.sun.irradiance_w_m2, nr::Light{}.irradiance_w_m2);
  expect_vec_eq(s.sun.direction_to_sun, glm::dvec3(0.0, 2.0, 0.0));
  EXPECT_FALSE(s.sky);
  EXPECT_FALSE(s.ambient_w_sr_m2);  // the caller's ambient stands
  const nr::SunSetup d = nr::set_up_sun(nullptr, {0.0, 2.0, 0.0}, nr::SunColour::Daylight);
  expect_vec_eq(d.sun.irradiance_w_m2, nr::daylight(glm::dvec3(0.0, 1.0, 0.0)).cloud_sun_irradiance_w_m2);
  EXPECT_TRUE(d.ambient_w_sr_m2);
}

TEST(SunSetup, ASceneWithoutASunGainsTheDefaultOne) {
  nr::Scene lamps = nr::make_scene("lamps");
  ASSERT_FALSE(lamps.sun);
  const nr::SunSetup s = nr::set_up_sun(&lamps, {0.0, 1.0, 0.0}, nr::SunColour::Scene);
  nr::place_sun(lamps, s);
  ASSERT_TRUE(lamps.sun);
  EXPECT_EQ(lamps.sun->kind, nr::LightKind::Sun);
  expect_vec_eq(lamps.sun->irradiance_w_m2, nr::Light{}.irradiance_w_m2);
  EXPECT_NO_THROW(nr::validate(lamps));
}

TEST(SunSetup, PlaceSunReplacesTheSkyOnlyWhenTheSetupBringsOne) {
  nr::Scene sky = nr::make_scene("sky");
  const auto before = sky.sky->atmosphere;
  nr::place_sun(sky, nr::set_up_sun(&sky, kLow, nr::SunColour::Scene));
  ASSERT_TRUE(sky.sky && sky.sky->atmosphere);
  EXPECT_NE(sky.sky->atmosphere, before);  // the tables of the new sun
  nr::Scene col = nr::make_scene("colonnade-sun");
  const std::optional<nr::Sky> kept = col.sky;
  nr::place_sun(col, nr::set_up_sun(&col, {0.0, 1.0, 0.0}, nr::SunColour::Daylight));
  EXPECT_EQ(col.sky.has_value(), kept.has_value());
  if (kept) expect_vec_eq(col.sky->zenith_radiance_w_sr_m2, kept->zenith_radiance_w_sr_m2);
}

TEST(SunSetup, BadDirectionsAreRefusedWithTheirReason) {
  const nr::Scene sky = nr::make_scene("sky");
  EXPECT_THROW(nr::set_up_sun(&sky, glm::dvec3(0.0), nr::SunColour::Scene), std::invalid_argument);
  EXPECT_THROW(nr::set_up_sun(nullptr, glm::dvec3(NAN, 1.0, 0.0), nr::SunColour::Scene), std::invalid_argument);
  try {
    nr::set_up_sun(&sky, {0.0, -1.0, 0.0}, nr::SunColour::Scene);  // below the horizon
    FAIL() << "a sun 90 degrees below the horizon was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("elevation"), std::string::npos) << e.what();
  }
  // Without the daylight a sun below the horizon is the caller's choice (a lamp-lit scene's sun).
  const nr::Scene col = nr::make_scene("colonnade-sun");
  EXPECT_NO_THROW(nr::set_up_sun(&col, {0.0, -1.0, 0.0}, nr::SunColour::Scene));
}
