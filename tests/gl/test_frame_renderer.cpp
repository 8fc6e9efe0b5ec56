// The frame pipeline (render/frame/frame_renderer.hpp): over a scene it is exactly the passes
// composed by hand (the clouds' shadow map, the shafts under it, the slices over them); alone it is
// the slicer without an underlay; with the reference method it is the CPU reference; the sun it is
// given lights the scene too, and moving it changes the frame; bad settings and missing clouds are
// refused.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/clouds/cloud_shadow.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kLumpyN = 24;  // lumpy_ball's grid

// A 16^3 lumpy cloud of 25 m voxels, 300 m above the sky scene's ground, in front of its camera.
CloudVolume sky_cloud() {
  CloudOptics o = grey_optics(0.05, 0.95);
  o.ambient_radiance = glm::dvec3(0.1);
  return cube_cloud(16, 25.0, [](int i, int j, int k) { return lumpy_ball(i, j, k, 16); }, o,
                    glm::dvec3(0.0, 300.0, -400.0), "lumpy");
}

Camera sky_camera() {
  Camera c;
  c.eye = {0.0, 2.0, 200.0};
  c.look_at = {0.0, 250.0, -400.0};
  c.width = 48;
  c.height = 32;
  c.fov_deg = 50.0;
  c.near_m = 0.5;
  c.far_m = 40000.0;
  return c;
}

Light light_of(const Scene& scene) {
  Light l;
  l.direction_to_sun = scene.sun->direction_to_sun;
  l.irradiance_w_m2 = scene.sun->irradiance_w_m2;
  return l;
}

FrameSettings small_settings() {
  FrameSettings s;
  s.slices.slices = 32;
  s.slices.light_res = 64;
  s.shafts = parse_shaft_method("raymarch:8");
  s.cloud_shadow_res = 64;
  return s;
}

bool same_pixels(const Image& a, const Image& b) { return a.width == b.width && a.rgba == b.rgba; }

TEST(FrameRenderer, OverASceneItIsTheShadowMapShaftsAndSlicesComposedByHand) {
  NIMBUS_REQUIRE_GL();
  const Scene scene = make_scene("sky");
  const Light light = light_of(scene);
  const FrameSettings settings = small_settings();
  const Camera cam = sky_camera();

  FrameRenderer frame(scene, light, settings);
  frame.set_clouds({sky_cloud()});
  FrameStats stats;
  const Image got = frame.render(cam, &stats);

  // The same passes by hand, as `nimbus render` composed them before the pipeline existed.
  CloudRenderer clouds({sky_cloud()});
  ShaftRenderer shafts(scene, settings.shaft_settings);
  const CloudShadowMap map = CloudShadowBuilder().build(clouds.clouds(), clouds.textures(), light, settings.cloud_shadow_res);
  shafts.set_cloud_shadow(&map);
  shafts.render(cam, settings.shafts);
  const SceneUnderlay under{shafts.color_texture(), shafts.distance_texture(), &scene};
  const Image want = clouds.render(cam, light, settings.slices, &under);

  ASSERT_TRUE(all_finite(got));
  EXPECT_TRUE(same_pixels(got, want)) << "rms difference " << rms_difference(got, want);
  // The cloud is in the picture and darker than nothing: some pixels differ from the scene alone.
  shafts.set_cloud_shadow(nullptr);
  const Image scene_only = shafts.render(cam, settings.shafts);
  EXPECT_GT(rms_difference(got, scene_only), 1e-4);
  EXPECT_EQ(got.metadata.at("method"), "slices over raymarch:8");
  EXPECT_EQ(got.metadata.at("clouds"), "lumpy");
  EXPECT_FALSE(got.metadata.at("slices").empty());
  EXPECT_EQ(got.metadata.at("device"), stats.device);
  EXPECT_NE(stats.summary.find("scene"), std::string::npos) << stats.summary;
  EXPECT_GT(stats.clouds.slices_drawn, 0);
}

// A spot given as a frame light joins the scene's lamps: the frame is, pixel for pixel, that of
// the scene with the spot among its own lamps, and the spot adds light.
TEST(FrameRenderer, ASpotJoinsTheScenesLamps) {
  NIMBUS_REQUIRE_GL();
  const Scene scene = make_scene("sky");
  const Light sun = light_of(scene);
  // A searchlight below the cloud, shining up at it.
  const Light spot = point_light({0.0, 150.0, -100.0}, glm::dvec3(1e8), {0.0, 150.0, -300.0}, 0.1, 0.2);
  Scene with_spot = scene;
  with_spot.lamps.push_back(spot);
  const Camera cam = sky_camera();
  FrameRenderer joined(scene, std::vector<Light>{sun, spot}, small_settings());
  FrameRenderer own(with_spot, std::vector<Light>{sun}, small_settings());
  FrameRenderer without(scene, std::vector<Light>{sun}, small_settings());
  for (FrameRenderer* f : {&joined, &own, &without}) f->set_clouds({sky_cloud()});
  const Image a = joined.render(cam), b = own.render(cam), c = without.render(cam);
  ASSERT_TRUE(all_finite(a) && all_finite(b));
  EXPECT_TRUE(same_pixels(a, b)) << "rms difference " << rms_difference(a, b);
  EXPECT_GT(rms_difference(a, c), 1e-4);
}

TEST(FrameRenderer, AloneItIsTheSlicerWithoutAnUnderlay) {
  NIMBUS_REQUIRE_GL();
  const CloudVolume cloud = cube_cloud(kLumpyN, 1.0 / kLumpyN, [](int i, int j, int k) { return lumpy_ball(i, j, k); },
                                       grey_optics(6.0, 0.9));
  const Camera cam = look_at_origin({0.4, 0.5, 2.5}, 40);
  Light light;
  light.direction_to_sun = {0.5, 0.7, 0.4};
  FrameSettings settings = small_settings();
  FrameRenderer frame(std::nullopt, light, settings);
  frame.set_clouds({cloud});
  const Image got = frame.render(cam);
  CloudRenderer slicer({cloud});
  const Image want = slicer.render(cam, light, settings.slices);
  EXPECT_TRUE(same_pixels(got, want)) << "rms difference " << rms_difference(got, want);
  EXPECT_EQ(got.metadata.at("method"), "cloud-slices");
}

TEST(FrameRenderer, TheReferenceMethodIsTheCpuReferenceAndTakesNoScene) {
  NIMBUS_REQUIRE_GL();
  const CloudVolume cloud = cube_cloud(kLumpyN, 1.0 / kLumpyN, [](int i, int j, int k) { return lumpy_ball(i, j, k); },
                                       grey_optics(6.0, 0.9));
  const Camera cam = look_at_origin({0.4, 0.5, 2.5}, 16);
  Light light;
  FrameSettings settings = small_settings();
  settings.method = CloudMethod::Reference;
  settings.reference.view_step_voxels = 0.5;
  settings.reference.shadow_step_voxels = 1.0;
  FrameRenderer frame(std::nullopt, light, settings);
  frame.set_clouds({cloud});
  FrameStats stats;
  const Image got = frame.render(cam, &stats);
  const Image want = render_cloud_reference({cloud}, cam, light, settings.reference);
  EXPECT_TRUE(same_pixels(got, want));
  EXPECT_EQ(got.metadata.at("method"), "cloud-reference");
  EXPECT_EQ(stats.device, "CPU (double precision)");
  EXPECT_THROW(FrameRenderer(make_scene("sky"), light, settings), std::invalid_argument);
}

TEST(FrameRenderer, TheSunLightsTheSceneAndMovingItChangesTheFrame) {
  NIMBUS_REQUIRE_GL();
  Scene scene = make_scene("sky");
  scene.sun.reset();  // the frame gives the scene the clouds' sun
  Light light;
  light.direction_to_sun = {0.4, 0.6, 0.3};
  light.irradiance_w_m2 = glm::dvec3(2.0);
  FrameRenderer frame(scene, light, small_settings());
  ASSERT_TRUE(frame.scene()->sun.has_value());
  EXPECT_EQ(frame.scene()->sun->direction_to_sun, light.direction_to_sun);
  EXPECT_EQ(frame.scene()->sun->irradiance_w_m2, light.irradiance_w_m2);
  frame.set_clouds({sky_cloud()});
  const Image a = frame.render(sky_camera());
  light.direction_to_sun = {-0.5, 0.3, -0.2};
  frame.set_light(light);
  EXPECT_EQ(frame.scene()->sun->direction_to_sun, light.direction_to_sun);
  const Image b = frame.render(sky_camera());
  ASSERT_TRUE(all_finite(a) && all_finite(b));
  EXPECT_GT(rms_difference(a, b), 1e-4);
  EXPECT_NE(a.metadata.at("lights"), b.metadata.at("lights"));
}

TEST(FrameRenderer, BadSettingsAndMissingCloudsAreRefused) {
  NIMBUS_REQUIRE_GL();
  Light light;
  FrameSettings bad = small_settings();
  bad.cloud_shadow_res = 8;
  try {
    FrameRenderer f(std::nullopt, light, bad);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cloud_shadow_res"), std::string::npos) << e.what();
  }
  bad = small_settings();
  bad.shafts = parse_shaft_method("reference");
  EXPECT_THROW(FrameRenderer(make_scene("sky"), light, bad), std::invalid_argument);
  bad = small_settings();
  bad.slices.slices = 1;
  EXPECT_THROW(FrameRenderer(std::nullopt, light, bad), std::invalid_argument);
  Light dark;
  dark.direction_to_sun = glm::dvec3(0.0);
  EXPECT_THROW(FrameRenderer(std::nullopt, dark, small_settings()), std::invalid_argument);

  // A spot whose cone is inside out is refused as it joins a scene, naming the cone.
  try {
    FrameRenderer f(make_scene("lamps"), point_light({0, 2, 0}, glm::dvec3(10.0), {0, -1, 0}, 0.5, 0.3), small_settings());
    FAIL() << "an inside-out spot joined a scene";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spot"), std::string::npos) << e.what();
  }

  FrameRenderer frame(std::nullopt, light, small_settings());
  EXPECT_THROW(frame.render(look_at_origin({0, 0, 3}, 8)), std::logic_error);
  EXPECT_THROW(frame.set_clouds({}), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
