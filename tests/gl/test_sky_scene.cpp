// The sky behind the scene (scene.hpp Sky): its gradient, where rays that meet nothing end, and
// the GPU frame agreeing with the CPU reference on the sky scene.
#include <gtest/gtest.h>

#include <cmath>

#include "nimbus/render/image/image_metrics.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SkyScene, GradientRunsFromTheHorizonToTheZenith) {
  const Sky sky;
  const glm::dvec3 up = sky_radiance(sky, {0, 1, 0}), flat = sky_radiance(sky, {1, 0, 0});
  const glm::dvec3 down = sky_radiance(sky, {0, -1, 0});
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(up[c], sky.zenith_radiance_w_sr_m2[c]);
    EXPECT_DOUBLE_EQ(flat[c], sky.horizon_radiance_w_sr_m2[c]);
    EXPECT_DOUBLE_EQ(down[c], sky.horizon_radiance_w_sr_m2[c]);
  }
  // sqrt(sin(elevation)): 30 degrees up is half of sqrt(0.5) of the way... w = sqrt(0.5).
  const glm::dvec3 mid = sky_radiance(sky, glm::normalize(glm::dvec3{std::sqrt(3.0), 1.0, 0.0}));
  EXPECT_NEAR(mid.z, sky.horizon_radiance_w_sr_m2.z + (sky.zenith_radiance_w_sr_m2.z - sky.horizon_radiance_w_sr_m2.z) * std::sqrt(0.5), 1e-12);
}

TEST(SkyScene, ValidationNamesTheSkyField) {
  Scene s = make_scene("sky");
  s.sky->distance_m = -1.0;
  try {
    validate(s);
    FAIL() << "a negative sky distance was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sky.distance_m"), std::string::npos) << e.what();
  }
  s = make_scene("sky");
  s.sky->zenith_radiance_w_sr_m2.y = NAN;
  EXPECT_THROW(validate(s), std::invalid_argument);
}

// A ray up into the open sky: the sky attenuated over its distance plus the sun's unshadowed
// airlight sigma_s p E (1 - e^(-sigma_t d)) / sigma_t (the sun is not attenuated on its way in).
TEST(SkyScene, ReferenceRayEndsAtTheSky) {
  const Scene s = make_scene("sky");
  const glm::dvec3 dir = glm::normalize(glm::dvec3{-0.3, 0.8, 0.2});
  const ReferenceSample r = reference_ray(s, {0, 2, 0}, dir);
  const double st = s.medium.extinction_per_m, d = s.sky->distance_m;
  const double cos_theta = glm::dot(-glm::normalize(s.sun->direction_to_sun), -dir);
  const double p = phase_value(s.medium.phase, cos_theta);
  const glm::dvec3 expected = sky_radiance(*s.sky, dir) * std::exp(-st * d) +
                              s.medium.scattering_per_m() * p * s.sun->irradiance_w_m2 * (1.0 - std::exp(-st * d)) / st;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.radiance[c] / expected[c], 1.0, 1e-4) << c;
  EXPECT_EQ(r.alpha, 1.0);
}

TEST(SkyScene, GpuFrameMatchesTheReference) {
  NIMBUS_REQUIRE_GL();
  const Scene s = make_scene("sky");
  Camera c = s.camera;
  c.width = 64;
  c.height = 36;
  ShaftRenderer r(s);
  const Image gpu = r.render(c, parse_shaft_method("raymarch:16"));
  const Image ref = render_reference(s, c);
  const ImageError e = compare_images(gpu, ref);
  // No occluder: the shadow ceiling puts every sample into the closed form, so only float
  // rounding separates them.
  EXPECT_LT(e.rel_rmse, 2e-3) << "max " << e.max_rel;
  for (std::size_t i = 3; i < gpu.rgba.size(); i += 4) ASSERT_EQ(gpu.rgba[i], 1.0f);
}

}  // namespace
}  // namespace nimbus::render
