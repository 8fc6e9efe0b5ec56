// The daylight model (render/scene/daylight.hpp) and the sky's light on surfaces (scene.hpp):
// directions, monotone dimming and reddening as the sun sets, and
// the ambient terms' limits.
#include <gtest/gtest.h>

#include <cmath>

#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/sky/view_state.hpp"

namespace nimbus::render {
namespace {

TEST(Daylight, SunDirectionFollowsElevationAndAzimuth) {
  const glm::dvec3 east = sun_direction(0.0, 90.0), north = sun_direction(0.0, 0.0), up = sun_direction(90.0, 17.0);
  EXPECT_NEAR(east.x, 1.0, 1e-12);
  EXPECT_NEAR(north.z, -1.0, 1e-12);  // y-up, -z north
  EXPECT_NEAR(up.y, 1.0, 1e-12);
  for (double el : {-10.0, 0.0, 12.5, 45.0, 89.9})
    for (double az : {0.0, 100.0, 359.0}) {
      const glm::dvec3 d = sun_direction(el, az);
      EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
      EXPECT_NEAR(std::asin(d.y) * 180.0 / M_PI, el, 1e-9);
    }
}

TEST(Daylight, SunDimsAndReddensAsItSetsAndSkyStaysFinite) {
  double last_g = 1e9, last_ratio = 0.0;
  for (double el = 90.0; el >= -10.0; el -= 2.5) {
    const Daylight d = daylight(el, 200.0);
    const glm::dvec3 e = d.sun.irradiance_w_m2;
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(e[c]) && e[c] >= 0.0);
      EXPECT_TRUE(std::isfinite(d.sky.zenith_radiance_w_sr_m2[c]) && d.sky.zenith_radiance_w_sr_m2[c] >= 0.0);
      EXPECT_TRUE(std::isfinite(d.sky.horizon_radiance_w_sr_m2[c]) && d.sky.horizon_radiance_w_sr_m2[c] >= 0.0);
      EXPECT_TRUE(std::isfinite(d.ambient_w_sr_m2[c]) && d.ambient_w_sr_m2[c] >= 0.0);
      // the clouds, 1.5 km up, see the sun through less air
      EXPECT_GE(d.cloud_sun_irradiance_w_m2[c], e[c]) << el;
    }
    ASSERT_TRUE(d.sky.atmosphere);
    EXPECT_EQ(sky_radiance(d.sky, {0.0, 1.0, 0.0}), d.sky.zenith_radiance_w_sr_m2);
    EXPECT_NEAR(sky_irradiance(d.sky, {0.0, 1.0, 0.0}).b, d.tables->sky_irradiance_up_w_m2.b, 1e-12);
    EXPECT_LE(e.g, last_g + 1e-12) << el;
    last_g = e.g;
    if (e.b > 1e-6) {
      EXPECT_GE(e.r / e.b, last_ratio - 1e-12) << "redder as it sets, at " << el;
      last_ratio = e.r / e.b;
    }
  }
  EXPECT_EQ(daylight(-5.0, 0.0).sun.irradiance_w_m2, glm::dvec3(0.0)) << "below the horizon";
  // After sunset the clouds stay lit a little longer: their horizon is 1.2 degrees lower.
  EXPECT_EQ(daylight(-0.5, 0.0).sun.irradiance_w_m2, glm::dvec3(0.0));
  EXPECT_GT(daylight(-0.5, 0.0).cloud_sun_irradiance_w_m2.r, 0.0);
  // The day's sky is far brighter than twilight's.
  EXPECT_GT(daylight(30.0, 0.0).ambient_w_sr_m2.g, 100.0 * daylight(-8.0, 0.0).ambient_w_sr_m2.g);
  // The sky scene's sun (6 x (1, 0.95, 0.88) at about 32 degrees) within 2 %.
  const glm::dvec3 e = daylight(32.0, 0.0).sun.irradiance_w_m2;
  const glm::dvec3 scene = 6.0 * glm::dvec3(1.0, 0.95, 0.88);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c] / scene[c], 1.0, 0.02);
  EXPECT_THROW(daylight(91.0, 0.0), std::invalid_argument);
  EXPECT_THROW(daylight(10.0, std::nan("")), std::invalid_argument);
}

TEST(Daylight, SkyIrradianceOnSurfaces) {
  Sky sky;
  sky.zenith_radiance_w_sr_m2 = glm::dvec3(0.1, 0.2, 0.4);
  sky.horizon_radiance_w_sr_m2 = glm::dvec3(0.3, 0.4, 0.5);
  const glm::dvec3 up = sky_irradiance(sky, glm::dvec3(0, 1, 0));
  EXPECT_NEAR(up.r, M_PI * 0.2, 1e-12);  // a uniform sky of radiance L gives pi L on a level surface
  EXPECT_NEAR(up.b, M_PI * 0.45, 1e-12);
  EXPECT_EQ(sky_irradiance(sky, glm::dvec3(0, -1, 0)), glm::dvec3(0.0));
  EXPECT_NEAR(sky_irradiance(sky, glm::dvec3(1, 0, 0)).g, 0.5 * up.g, 1e-12);
}

}  // namespace
// The viewer asks for the daylight every frame: the same sun must give the same tables, not a
// rebuild (a sky view and aerial perspective per frame once cost ~200 ms: the tables keep the
// direction normalised again, an ulp off the caller's; and validating a view state built the sky
// scene, whose own sun evicted the viewer's).
TEST(Daylight, TheSameSunReusesItsTables) {
  const Daylight a = daylight(35.0, 135.0);
  const Daylight b = daylight(35.0, 135.0);
  EXPECT_EQ(a.tables.get(), b.tables.get());
  const glm::dvec3 odd = glm::normalize(glm::dvec3(0.3, 0.7, -0.2)) * 3.0;  // not unit: normalised on use
  EXPECT_EQ(daylight(odd).tables.get(), daylight(odd).tables.get());
  ViewState s = default_view_state();
  s.scene = "sky";
  const Daylight before = daylight(s.sky.sun_elevation_deg, s.sky.sun_azimuth_deg);
  validate(s);
  EXPECT_EQ(daylight(s.sky.sun_elevation_deg, s.sky.sun_azimuth_deg).tables.get(), before.tables.get());
}

}  // namespace nimbus::render
