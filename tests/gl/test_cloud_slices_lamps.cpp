// The half-angle slicer lit by lamps (point lights and spots; light.hpp) against the CPU
// reference of the same model: near and far, front- and back-lit, isotropic and forward
// scattering; a spot's cone across the cloud; two lamps in two passes, or the strongest alone;
// the steam of the steam-lamp scene at 128 slices (within 1 % relative RMSE).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 24;
constexpr double kVoxel = 1.0 / kN;

struct LampCase {
  std::string name;
  glm::dvec3 direction;  // from the ball's centre towards the lamp
  double distance_m;     // the ball's radius is 0.45 m
  double g;              // Henyey-Greenstein asymmetry
  double tolerance;      // relative RMSE over covered pixels
};

void PrintTo(const LampCase& c, std::ostream* os) { *os << c.name; }

std::vector<CloudVolume> ball(double g) {
  CloudOptics o = grey_optics(8.0, 0.9);
  o.phase = Phase{PhaseKind::HenyeyGreenstein, g};
  return {cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o)};
}

ImageError report(const std::string& name, const Image& img, const Image& ref) {
  const ImageError e = compare_images(img, ref);
  std::printf("[ lamp slices vs reference ] %s: rel RMSE %.4f, bias %+.4f over %zu pixels\n", name.c_str(), e.rel_rmse,
              e.mean_bias, e.pixels);
  return e;
}

class LampAgainstReference : public ::testing::TestWithParam<LampCase> {};

// Measured (llvmpipe, 64 slices): rel RMSE 0.1-0.6 % (the closest lamp, 0.75 m from the centre of
// a 0.45 m ball, highest).
TEST_P(LampAgainstReference, RelativeRmseWithinTolerance) {
  NIMBUS_REQUIRE_GL();
  const LampCase& p = GetParam();
  const std::vector<CloudVolume> clouds = ball(p.g);
  const Camera cam = look_at_origin({0.4, 0.3, 2.5}, 64, 30.0);
  const Light lamp = point_light(p.distance_m * glm::normalize(p.direction), glm::dvec3(p.distance_m * p.distance_m));
  const Image ref = render_cloud_reference(clouds, cam, lamp, quick_reference());
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  CloudFrameStats st;
  const Image img = r.render(cam, lamp, s, nullptr, &st);
  const ImageError e = report(p.name, img, ref);
  EXPECT_GT(e.pixels, 1000u);
  EXPECT_LT(e.rel_rmse, p.tolerance) << p.name;
  EXPECT_EQ(st.light_passes, 1);
  double alpha_err = 0.0;
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) alpha_err = std::max(alpha_err, std::abs(double(img.rgba[i]) - ref.rgba[i]));
  EXPECT_LT(alpha_err, 0.02) << p.name << ": largest |alpha - reference|";
  EXPECT_NE(img.metadata.at("light").find("point"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(CloudSlices, LampAgainstReference,
                         ::testing::Values(LampCase{"front_far_isotropic", {0.5, 0.6, 0.8}, 3.0, 0.0, 0.01},
                                           LampCase{"back_far_isotropic", {-0.3, 0.5, -0.8}, 3.0, 0.0, 0.01},
                                           LampCase{"front_near_hg", {0.5, 0.6, 0.8}, 0.75, 0.6, 0.015},
                                           LampCase{"back_near_hg", {-0.3, 0.5, -0.8}, 0.75, 0.6, 0.015},
                                           LampCase{"side_near_isotropic", {1.0, 0.1, 0.0}, 0.75, 0.0, 0.015}),
                         [](const ::testing::TestParamInfo<LampCase>& param) { return param.param.name; });

// A spot whose cone edge crosses the ball: the lit part and the dark part agree with the
// reference, and the spot lights less than the lamp it is cut from.
TEST(CloudSlicesLamps, SpotConeAcrossTheBallMatchesReference) {
  NIMBUS_REQUIRE_GL();
  const std::vector<CloudVolume> clouds = ball(0.0);
  const Camera cam = look_at_origin({0.4, 0.3, 2.5}, 64, 30.0);
  const glm::dvec3 at{0.0, 2.0, 0.0};
  // Aimed 0.25 m to the side of the centre, cone 5-9 degrees: the edge runs through the ball.
  const Light spot = point_light(at, glm::dvec3(4.0), glm::normalize(glm::dvec3(0.25, 0.0, 0.0) - at),
                                      5.0 * M_PI / 180.0, 9.0 * M_PI / 180.0);
  const Image ref = render_cloud_reference(clouds, cam, spot, quick_reference());
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  const Image img = r.render(cam, spot, s);
  EXPECT_LT(report("spot", img, ref).rel_rmse, 0.015);
  const Image full = r.render(cam, point_light(at, glm::dvec3(4.0)), s);
  double lit = 0.0, all = 0.0;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4) {
    lit += img.rgba[i];
    all += full.rgba[i];
  }
  EXPECT_GT(lit, 0.05 * all);
  EXPECT_LT(lit, 0.8 * all);
}

// Two lamps: one pass each, their radiance adding up to the reference of both; with max_lights 1
// the weaker is left out (and named), and the frame is the stronger lamp's alone.
TEST(CloudSlicesLamps, TwoLampsAddAndTheWeakerIsLeftOutByMaxLights) {
  NIMBUS_REQUIRE_GL();
  const std::vector<CloudVolume> clouds = ball(0.3);
  const Camera cam = look_at_origin({0.4, 0.3, 2.5}, 64, 30.0);
  const Light strong = point_light(2.0 * glm::normalize(glm::dvec3(0.5, 0.6, 0.8)), glm::dvec3(4.0));
  const Light weak = point_light(2.0 * glm::normalize(glm::dvec3(-0.3, 0.5, -0.8)), glm::dvec3(2.0));
  const std::vector<Light> both = {weak, strong};
  const Image ref = render_cloud_reference(clouds, cam, both, quick_reference());
  CloudRenderer r(clouds, GL_R32F);
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  CloudFrameStats st;
  const Image img = r.render(cam, both, s, nullptr, &st);
  EXPECT_EQ(st.light_passes, 2);
  EXPECT_LT(report("two lamps", img, ref).rel_rmse, 0.01);
  EXPECT_EQ(img.metadata.count("lights_left_out"), 0u);
  s.max_lights = 1;
  const Image one = r.render(cam, both, s, nullptr, &st);
  EXPECT_EQ(st.light_passes, 1);
  ASSERT_EQ(one.metadata.count("lights_left_out"), 1u);
  EXPECT_NE(one.metadata.at("lights_left_out").find("I_w_sr 2,2,2"), std::string::npos);
  const Image strong_alone = r.render(cam, strong, s);
  ASSERT_EQ(one.rgba.size(), strong_alone.rgba.size());
  for (std::size_t i = 0; i < one.rgba.size(); ++i) ASSERT_EQ(one.rgba[i], strong_alone.rgba[i]) << "value " << i;
  EXPECT_GT(report("max_lights 1 vs both", one, ref).rel_rmse, 0.1);  // the weaker lamp's share is missing
}

// A lamp takes the octaves method: the light volume (photons from the sun) refuses it.
TEST(CloudSlicesLamps, LightVolumeRefusesALamp) {
  NIMBUS_REQUIRE_GL();
  CloudRenderer r(ball(0.0), GL_R32F);
  CloudSliceSettings s;
  s.multiple.method = MultipleScatteringMethod::LightVolume;
  LightVolume v;
  v.size[0] = v.size[1] = v.size[2] = 4;
  v.cell_m = glm::dvec3(0.25);
  v.world_min = glm::dvec3(-0.5);
  v.light_direction = {0, -1, 0};
  v.fluence_rgb.assign(3 * 64, 0.0f);
  v.flux_xyz.assign(3 * 64, 0.0f);
  v.quadrupole.assign(5 * 64, 0.0f);
  r.set_light_volume(v);
  try {
    r.render(look_at_origin({0, 0, 2.5}, 16), point_light({0, 2, 0}, glm::dvec3(1.0)), s);
    FAIL() << "a lamp with the light volume must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("octaves"), std::string::npos) << e.what();
  }
}

// The steam of the teacup (Hoffmann 2007) under the street lamp of scene steam-lamp
// (clouds alone), at 128 slices, within 1 % relative RMSE of the reference. The steam at 4 mm
// voxels (the preset's own 2 mm in CI time would be 8 times the reference's work).
TEST(CloudSlicesLamps, SteamUnderTheLampWithinOnePercentAt128Slices) {
  NIMBUS_REQUIRE_GL();
  const Scene scene = make_scene("steam-lamp");
  CloudOptics optics;
  optics.extinction_per_m = *scene.cloud_extinction_per_m;
  optics.phase = parse_cloud_phase("dual:0.7,-0.25,0.8");
  const std::vector<CloudVolume> steam = {generate_preset_cloud(load_preset_cloud("steam"), 0.004, 0.0, optics)};
  Camera cam = scene.camera;  // its view, narrowed onto the steam
  cam.look_at = {0.0, 0.14, 0.0};
  cam.fov_deg = 22.0;
  cam.width = 96;
  cam.height = 96;
  const Light lamp = point_light(scene.lamps[0].position_m, scene.lamps[0].intensity_w_sr);
  CloudReferenceSettings rs;
  rs.view_step_voxels = 0.5;
  rs.shadow_step_voxels = 1.0;
  const Image ref = render_cloud_reference(steam, cam, lamp, rs);
  CloudRenderer r(steam, GL_R16F);
  CloudSliceSettings s;
  s.slices = 128;
  s.light_res = 256;
  s.jitter = false;
  const Image img = r.render(cam, lamp, s);
  const ImageError e = report("steam under the lamp", img, ref);
  EXPECT_GT(e.pixels, 500u);
  EXPECT_LT(e.rel_rmse, 0.01);
}

}  // namespace
}  // namespace nimbus::render
