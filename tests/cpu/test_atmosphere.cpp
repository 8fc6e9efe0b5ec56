// The physical sky (render/media/atmosphere_tables.hpp) against its brute-force double-precision
// reference (render/reference/atmosphere_reference.hpp) and against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>

#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/reference/atmosphere_reference.hpp"

namespace nimbus::render {
namespace {
namespace glsl {  // the shared maps, compiled here as C++ (internal linkage: the library has its own copy)
using namespace glm;
#include "lib/atmosphere_map.glsl"
}  // namespace glsl

constexpr double kDeg = M_PI / 180.0;

// A direction at an elevation, at an azimuth measured from the sun's.
glm::dvec3 view_dir(const glm::dvec3& sun, double elevation_deg, double azimuth_from_sun_deg) {
  const glm::dvec3 sh = glm::normalize(glm::dvec3(sun.x, 0.0, sun.z));
  const glm::dvec3 side{-sh.z, 0.0, sh.x};
  const double e = elevation_deg * kDeg, a = azimuth_from_sun_deg * kDeg;
  return std::cos(e) * (std::cos(a) * sh + std::sin(a) * side) + glm::dvec3(0.0, std::sin(e), 0.0);
}

glm::dvec3 sun_at(double elevation_deg) {
  const double e = elevation_deg * kDeg;
  return {0.8 * std::cos(e), std::sin(e), -0.6 * std::cos(e)};
}

double max_rel(const glm::dvec3& a, const glm::dvec3& b) {
  double m = 0.0;
  for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(a[c] - b[c]) / std::abs(b[c]));
  return m;
}

const AtmosphereTables& tables_at(double elevation_deg) {
  static std::map<double, std::shared_ptr<const AtmosphereTables>> cache;
  auto& t = cache[elevation_deg];
  if (!t) t = build_atmosphere_tables(Atmosphere{}, AtmosphereView{2.0, sun_at(elevation_deg), 40000.0});
  return *t;
}

TEST(Atmosphere, VerticalOpticalDepthHasAClosedForm) {
  // Straight up, altitude is distance: tau = sigma_R H_R (1 - e^{-Z/H_R}) + sigma_M H_M (1 - e^{-Z/H_M})
  // + sigma_O w (the ozone tent's area), Z the atmosphere's thickness.
  const Atmosphere a;
  const double Z = a.top_radius_m - a.bottom_radius_m;
  const glm::dvec3 tau = a.rayleigh_scattering_per_m * a.rayleigh_scale_height_m * (1.0 - std::exp(-Z / a.rayleigh_scale_height_m)) +
                         glm::dvec3(a.mie_extinction_per_m * a.mie_scale_height_m * (1.0 - std::exp(-Z / a.mie_scale_height_m))) +
                         a.ozone_absorption_per_m * a.ozone_half_width_m;
  const glm::dvec3 exact = glm::exp(-tau);
  EXPECT_LT(max_rel(reference_transmittance(a, 0.0, 1.0), exact), 1e-9);
  // the table: 64 midpoint steps over the ozone tent's kinks
  EXPECT_LT(max_rel(table_transmittance(tables_at(33.0), 0.0, 1.0), exact), 2e-3);
}

TEST(Atmosphere, MapsRoundTripTheirTexels) {
  const Atmosphere a;
  for (int y = 0; y < glsl::ATM_TRANSMITTANCE_H; y += 7) {
    for (int x = 0; x < glsl::ATM_TRANSMITTANCE_W; x += 17) {
      const TransmittanceTexel q = transmittance_texel(a, x, y);
      const glm::vec2 c = glsl::atm_transmittance_coord(float(a.bottom_radius_m), float(a.top_radius_m), float(q.altitude_m), float(q.mu));
      EXPECT_NEAR(c.x, x, 0.05) << x << "," << y;
      EXPECT_NEAR(c.y, y, 0.05) << x << "," << y;
      EXPECT_GE(q.mu, horizon_cos(a, q.altitude_m) - 1e-9);  // no texel below the horizon
    }
  }
  for (double h : {0.0, 2.0, 1500.0, 20000.0}) {
    for (int j = 0; j <= 20; ++j) {
      for (int i = 0; i <= 10; ++i) {
        const double u = i / 10.0, v = j / 20.0;
        const ViewTexel q = view_texel(a, h, u, v);
        const glm::vec2 uv = glsl::atm_view_uv(float(q.cos_phi), float(q.cos_theta), float(horizon_cos(a, h)));
        EXPECT_NEAR(uv.x, u, 2e-3) << h << " " << u << " " << v;
        EXPECT_NEAR(uv.y, v, 2e-3) << h << " " << u << " " << v;
      }
    }
  }
}

TEST(Atmosphere, TransmittanceTableMatchesTheReference) {
  const Atmosphere a;
  const AtmosphereTables& t = tables_at(33.0);
  for (double h : {0.0, 1500.0, 8000.0, 30000.0, 80000.0}) {
    for (double mu : {1.0, 0.7, 0.4, 0.2, 0.1, 0.05}) {
      const glm::dvec3 T = table_transmittance(t, h, mu), R = reference_transmittance(a, h, mu);
      EXPECT_LT(max_rel(T, R), 0.006) << "h " << h << " mu " << mu;
    }
  }
  // Below the horizon the sun is hidden: no light, and no NaN on the way.
  const glm::dvec3 hidden = table_sun_irradiance(t, 0.0, -0.05);
  EXPECT_EQ(hidden, glm::dvec3(0.0));
  EXPECT_EQ(reference_transmittance(a, 0.0, -0.05), glm::dvec3(0.0));
}

TEST(Atmosphere, MultipleScatteringTableMatchesTheReference) {
  const Atmosphere a;
  const AtmosphereTables& t = tables_at(33.0);
  for (double h : {0.0, 2000.0, 10000.0, 40000.0}) {
    // The sun at least 11.5 degrees up: within 1.5 %.
    for (double mu_s : {0.9, 0.5, 0.2}) {
      EXPECT_LT(max_rel(table_multiple_scattering(t, h, mu_s), reference_multiple_scattering(a, h, mu_s)), 0.015) << h << " " << mu_s;
    }
    // At the horizon Psi falls steeply and the 32 columns interpolate it: within 3 % of the day's value.
    const glm::dvec3 day = reference_multiple_scattering(a, h, 0.5);
    for (double mu_s : {0.0, -0.1}) {
      const glm::dvec3 d = table_multiple_scattering(t, h, mu_s) - reference_multiple_scattering(a, h, mu_s);
      for (int c = 0; c < 3; ++c) EXPECT_LT(std::abs(d[c]), 0.03 * day[c]) << h << " " << mu_s;
    }
  }
}

// The sky's radiance from the table against the brute-force integral, for a sun at `elevation`,
// within `tolerance` at least 12 degrees from the horizon and `near_horizon` at 3 degrees above
// and 10 below it.
void expect_sky_matches(double elevation, double tolerance, double near_horizon) {
  const Atmosphere a;
  const AtmosphereTables& t = tables_at(elevation);
  const glm::dvec3 sun = sun_at(elevation);
  for (double el : {90.0, 40.0, 12.0, 3.0, -10.0}) {
    for (double az : {0.0, 100.0, 180.0}) {
      if (el == 90.0 && az > 0.0) continue;
      const glm::dvec3 d = view_dir(sun, el, az);
      const AtmosphereRadiance R = reference_sky(a, AtmosphereRay{2.0, sun, d});
      const glm::dvec3 L = table_sky_radiance(t, d);
      EXPECT_LT(max_rel(L, R.inscattered_w_sr_m2), std::abs(el) >= 12.0 ? tolerance : near_horizon) << "sun " << elevation << " view elevation " << el << " azimuth " << az;
    }
  }
}

TEST(Atmosphere, SkyViewMatchesTheReferenceAfternoon) { expect_sky_matches(33.0, 0.02, 0.02); }
TEST(Atmosphere, SkyViewMatchesTheReferenceLowSun) { expect_sky_matches(5.0, 0.02, 0.02); }
// After sunset the light left is high above, and near the horizon the 64 columns of Psi_ms
// interpolate a function that falls by orders of magnitude: 3 % and 8 %.
TEST(Atmosphere, SkyViewMatchesTheReferenceAfterSunset) { expect_sky_matches(-4.0, 0.03, 0.08); }

TEST(Atmosphere, AerialPerspectiveMatchesTheReference) {
  const Atmosphere a;
  const glm::dvec3 sun = sun_at(33.0);
  const AtmosphereTables& t = tables_at(33.0);
  for (double el : {20.0, 3.0}) {
    for (double az : {0.0, 90.0}) {
      for (double D : {1000.0, 7000.0, 30000.0}) {
        const glm::dvec3 d = view_dir(sun, el, az);
        const AtmosphereRadiance R = reference_sky(a, AtmosphereRay{2.0, sun, d, D});
        const AerialPerspective A = table_aerial_perspective(t, d, D);
        EXPECT_LT(max_rel(A.inscattered_w_sr_m2, R.inscattered_w_sr_m2), 0.025) << el << " " << az << " " << D;
        EXPECT_LT(max_rel(A.transmittance, R.transmittance), 2e-3) << el << " " << az << " " << D;
      }
    }
  }
  // Nothing in front of the viewer: no haze.
  const AerialPerspective zero = table_aerial_perspective(t, view_dir(sun, 10.0, 30.0), 0.0);
  EXPECT_EQ(zero.inscattered_w_sr_m2, glm::dvec3(0.0));
  EXPECT_EQ(zero.transmittance, glm::dvec3(1.0));
}

TEST(Atmosphere, DaySkyIsBlueAndBrighterTowardTheHorizon) {
  const AtmosphereTables& t = tables_at(33.0);
  const glm::dvec3 sun = sun_at(33.0);
  const glm::dvec3 zenith = table_sky_radiance(t, {0.0, 1.0, 0.0});
  const glm::dvec3 low = table_sky_radiance(t, view_dir(sun, 5.0, 90.0));
  EXPECT_GT(zenith.z, 2.0 * zenith.x);  // blue
  auto lum = [](const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
  EXPECT_GT(lum(low), 1.3 * lum(zenith));  // darker at the zenith than at the horizon
  EXPECT_LT(low.z / low.x, zenith.z / zenith.x);  // and paler toward the horizon
  // The ground-level sun: reddened and dimmed by the air, not brighter than above it.
  const glm::dvec3 E = table_sun_irradiance(t, 0.0, sun.y);
  const glm::dvec3 E0 = Atmosphere{}.solar_irradiance_w_m2;
  for (int c = 0; c < 3; ++c) EXPECT_LT(E[c], E0[c]);
  EXPECT_LT(E.z / E.x, E0.z / E0.x);
}

TEST(Atmosphere, TheSkyDarkensThroughTwilightWithoutNaN) {
  double previous = 1e30;
  for (double elevation : {33.0, 5.0, 0.0, -2.0, -4.0, -6.0, -8.0, -10.0}) {
    const AtmosphereTables& t = tables_at(elevation);
    for (const AtmosphereTable* table : {&t.sky_view, &t.aerial_scattering, &t.aerial_transmittance, &t.multiple_scattering, &t.transmittance}) {
      for (const glm::vec3& v : table->texels) {
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << elevation;
        ASSERT_GE(std::min({v.x, v.y, v.z}), 0.0f) << elevation;
      }
    }
    const double zenith = table_sky_radiance(t, {0.0, 1.0, 0.0}).y;
    EXPECT_LT(zenith, previous) << elevation;
    previous = zenith;
    if (elevation <= -4.0) EXPECT_EQ(table_sun_irradiance(t, 0.0, sun_at(elevation).y), glm::dvec3(0.0));
  }
  // Civil twilight's end: the zenith is at least 100 times darker than in the afternoon.
  EXPECT_LT(table_sky_radiance(tables_at(-6.0), {0.0, 1.0, 0.0}).y, 0.01 * table_sky_radiance(tables_at(33.0), {0.0, 1.0, 0.0}).y);
}

TEST(Atmosphere, NoAirNoSky) {
  // Without scattering (and a black ground), nothing is scattered toward the viewer, whatever the sun.
  Atmosphere a;
  a.rayleigh_scattering_per_m = glm::dvec3(0.0);
  a.mie_scattering_per_m = 0.0;
  a.ground_albedo = 0.0;
  const auto t = build_atmosphere_tables(a, AtmosphereView{2.0, sun_at(20.0), 40000.0});
  for (const glm::vec3& v : t->sky_view.texels) EXPECT_EQ(v, glm::vec3(0.0f));
  EXPECT_EQ(t->sky_irradiance_up_w_m2, glm::dvec3(0.0));
  // The view-independent tables are reused for another sun, and equal a fresh build.
  const auto again = build_atmosphere_tables(a, AtmosphereView{2.0, sun_at(50.0), 40000.0}, t);
  const auto fresh = build_atmosphere_tables(a, AtmosphereView{2.0, sun_at(50.0), 40000.0});
  EXPECT_EQ(again->multiple_scattering.texels, fresh->multiple_scattering.texels);
  EXPECT_EQ(again->transmittance.texels, fresh->transmittance.texels);
  EXPECT_EQ(again->timing.multiple_scattering_ms, 0.0);
}

TEST(Atmosphere, BadInputIsRefusedNamingTheField) {
  Atmosphere a;
  a.mie_g = 1.0;
  EXPECT_THROW(
      {
        try {
          build_atmosphere_tables(a, AtmosphereView{});
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("mie_g"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
  EXPECT_THROW(build_atmosphere_tables(Atmosphere{}, AtmosphereView{-1.0}), std::invalid_argument);
  EXPECT_THROW(build_atmosphere_tables(Atmosphere{}, AtmosphereView{2.0, glm::dvec3(0.0)}), std::invalid_argument);
  EXPECT_THROW(build_atmosphere_tables(Atmosphere{}, AtmosphereView{2.0, glm::dvec3(NAN, 1, 0)}), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
