// The half-angle slicer over an opaque scene (SceneUnderlay): surfaces in front of a cloud hide
// it, a surface between clouds hides those behind, a cloud in front of the scene covers it, and
// fog in front of a cloud attenuates it by exp(-sigma t) and adds the closed-form airlight of the
// sun and of a point light.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/core/phase.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 24;
constexpr double kVoxel = 1.0 / kN;

// A scene with only lights and fog (the clouds are drawn over its colour/distance textures).
Scene fog_scene(double sigma_t, double albedo, const Phase& phase) {
  Scene s;
  s.name = "underlay-test";
  s.medium.extinction_per_m = sigma_t;
  s.medium.albedo = albedo;
  s.medium.phase = phase;
  s.sun = Light{};
  s.sun->direction_to_sun = {0.3, 0.8, 0.5};
  s.sun->irradiance_w_m2 = {2.0, 2.5, 3.0};
  return s;
}

// Camera-sized textures: a constant colour, and a distance per pixel from `dist(x, y)` (image
// row y = 0 at the top).
struct Underlay {
  GlTexture color, distance;
  SceneUnderlay u;
  Underlay(const Camera& cam, const glm::vec4& rgba, const std::function<float(int, int)>& dist, const Scene* scene) {
    std::vector<float> c, d;
    for (int gy = 0; gy < cam.height; ++gy)
      for (int x = 0; x < cam.width; ++x) {
        for (int k = 0; k < 4; ++k) c.push_back(rgba[k]);
        d.push_back(dist(x, cam.height - 1 - gy));
      }
    color = texture_from(GL_RGBA32F, cam.width, cam.height, c);
    distance = texture_from(GL_R32F, cam.width, cam.height, d);
    u.color_texture = color.id();
    u.distance_texture = distance.id();
    u.scene = scene;
  }
};

TEST(CloudSlicesUnderlay, SurfacesHideWhatIsBehindThemAndCloudsCoverTheScene) {
  NIMBUS_REQUIRE_GL();
  // Two clouds one behind the other, lit from the camera's side so the back one does not shadow
  // the front one; a surface at 1 m (in front of both), at the plane z = 0 (between them) and at
  // 50 m (behind both), in three vertical bands.
  const auto ball = [](int i, int j, int k) { return lumpy_ball(i, j, k); };
  const CloudVolume front = cube_cloud(kN, kVoxel, ball, grey_optics(8.0), {0, 0, 0.55}, "front");
  const CloudVolume back = cube_cloud(kN, kVoxel, ball, grey_optics(8.0), {0, 0, -0.55}, "back");
  CloudRenderer both({front, back}, GL_R32F);
  CloudRenderer front_only({front}, GL_R32F);
  const Camera cam = look_at_origin({0.0, 0.0, 3.5}, 48, 24.0);
  Light light;
  light.direction_to_sun = {0.2, 0.3, 1.0};
  CloudSliceSettings s;
  s.slices = 96;
  s.light_res = 128;
  const Scene scene = fog_scene(0.0, 1.0, Phase{});  // no fog
  const glm::vec4 scene_rgba(0.2f, 0.3f, 0.4f, 1.0f);
  const auto band = [&](int x) { return x < 16 ? 0 : x < 32 ? 1 : 2; };
  Underlay under(cam, scene_rgba, [&](int x, int y) {
    const glm::dvec3 d = pixel_ray(cam, x, y);
    return band(x) == 0 ? 1.0f : band(x) == 1 ? static_cast<float>(cam.eye.z / -d.z) : 50.0f;
  }, &scene);
  const Image out = both.render(cam, light, s, &under.u);
  const Image clouds = both.render(cam, light, s);
  const Image front_alone = front_only.render(cam, light, s);
  int covered[3] = {0, 0, 0};
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const float* o = out.pixel(x, y);
      const float* c = band(x) == 1 ? front_alone.pixel(x, y) : clouds.pixel(x, y);
      covered[band(x)] += c[3] > 0.5f;
      EXPECT_EQ(o[3], 1.0f);
      for (int k = 0; k < 3; ++k) {
        if (band(x) == 0) {  // the surface hides both clouds
          EXPECT_NEAR(o[k], scene_rgba[k], 1e-6) << x << "," << y;
        } else if (band(x) == 1) {  // only the front cloud (its own slices: measured <= 0.1 % off)
          EXPECT_NEAR(o[k], scene_rgba[k] * (1.0f - c[3]) + c[k], 0.005 * (scene_rgba[k] + c[k])) << x << "," << y;
        } else {  // both clouds over the scene
          EXPECT_NEAR(o[k], scene_rgba[k] * (1.0f - c[3]) + c[k], 1e-5) << x << "," << y;
        }
      }
    }
  for (int b = 1; b < 3; ++b) EXPECT_GT(covered[b], 100) << "band " << b;
}

// The camera inside a homogeneous box (z = 0.3, in its plateau) and a surface through it at
// z = 0: lit by the ambient term alone over a black scene, out = albedo L A with A = 1 -
// exp(-sigma 0.3 / |dir.z|). The slab around the eye reaches back to it and the slab holding the
// surface ends there, so with uniform density every sample position gives the same sum: exact
// with and without jitter (measured 8.7e-7).
TEST(CloudSlicesUnderlay, SurfaceInsideACloudCutsIt) {
  NIMBUS_REQUIRE_GL();
  CloudOptics o = grey_optics(3.0, 0.9);
  o.ambient_radiance = glm::dvec3(1.0);
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int, int, int) { return 1.0f; }, o)}, GL_R32F);
  Camera cam = look_at_origin({0.0, 0.0, 0.3}, 48, 60.0);
  cam.look_at = {0.0, 0.0, -1.0};
  Light light;
  light.irradiance_w_m2 = glm::dvec3(0.0);
  const Scene scene = fog_scene(0.0, 1.0, Phase{});
  Underlay under(cam, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), [&](int x, int y) {
    return static_cast<float>(cam.eye.z / -pixel_ray(cam, x, y).z);
  }, &scene);
  for (bool jitter : {true, false}) {
    CloudSliceSettings s;
    s.slices = 64;
    s.light_res = 64;
    s.jitter = jitter;
    const Image out = r.render(cam, light, s, &under.u);
    double worst = 0.0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const double dz = std::abs(pixel_ray(cam, x, y).z);
        const double expected = 1.0 - std::exp(-o.extinction_per_m * cam.eye.z / dz);
        worst = std::max(worst, std::abs(out.pixel(x, y)[1] / 0.9 - expected));
      }
    EXPECT_LT(worst, 1e-5) << "largest |alpha in front of the surface - closed form|, jitter " << jitter;
  }
}

// An opaque box seen through fog: where the box covers the pixel, out = C exp(-sigma t) +
// A_fog(0, t), t the distance to its front face, A_fog the closed forms (sun: sigma_s p E
// (1 - e^{-sigma t}) / sigma; point light: the double-precision quadrature of Sun et al.); the
// scene behind it is hidden, and where no cloud is, the scene shows unchanged.
TEST(CloudSlicesUnderlay, FogAttenuatesTheCloudAndAddsItsAirlight) {
  NIMBUS_REQUIRE_GL();
  CloudRenderer r({cube_cloud(kN, kVoxel, [](int, int, int) { return 1.0f; }, grey_optics(300.0))}, GL_R32F);
  const Camera cam = look_at_origin({0.0, 0.0, 3.0}, 48, 30.0);
  Light light;
  light.direction_to_sun = {0.3, 0.8, 0.5};
  CloudSliceSettings s;
  s.slices = 96;
  s.light_res = 64;
  const Phase fog_phase{PhaseKind::HenyeyGreenstein, 0.3};
  Scene scene = fog_scene(0.4, 0.8, fog_phase);
  const Light lamp = bulb_light({1.5, 1.0, 2.0}, {4.0, 3.0, 2.0}, 0.05);
  scene.lamps.push_back(lamp);
  const glm::vec4 sky(5.0f, 6.0f, 7.0f, 1.0f);
  Underlay under(cam, sky, [](int, int) { return 0.0f; }, &scene);  // no surface: sky everywhere
  const Image out = r.render(cam, light, s, &under.u);
  const Image clouds = r.render(cam, light, s);
  const double plateau = 0.5 * (kN - 1) * kVoxel, face = plateau + kVoxel;
  const double sigma = scene.medium.extinction_per_m, sigma_s = scene.medium.scattering_per_m();
  const glm::dvec3 to_sun = glm::normalize(scene.sun->direction_to_sun);
  int checked = 0, clear = 0;
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 d = pixel_ray(cam, x, y);
      const float* c = clouds.pixel(x, y);
      const float* o = out.pixel(x, y);
      if (c[3] == 0.0f) {
        for (int k = 0; k < 3; ++k) EXPECT_EQ(o[k], sky[k]) << x << "," << y;
        ++clear;
        continue;
      }
      const double t = (face - cam.eye.z) / d.z;  // to the support's front face
      const glm::dvec3 q = cam.eye + t * d;
      if (c[3] < 1.0f || std::abs(q.x) > plateau || std::abs(q.y) > plateau) continue;
      const double sun = sigma_s * phase_value(fog_phase, glm::dot(to_sun, d)) * (1.0 - std::exp(-sigma * t)) / sigma;
      const glm::dvec3 to_lamp = lamp.position_m - cam.eye;
      SegmentQuery seg;
      seg.sigma_t = sigma;
      seg.sigma_s = sigma_s;
      seg.Dsv = glm::length(to_lamp);
      seg.cos_gamma = glm::dot(d, to_lamp) / seg.Dsv;
      seg.sin_gamma = glm::length(glm::cross(d, to_lamp)) / seg.Dsv;
      seg.x0 = 0.0;
      seg.x1 = t;
      seg.phase = fog_phase;
      const double point = segment_airlight_quadrature(seg);
      for (int k = 0; k < 3; ++k) {
        const double expected = c[k] * std::exp(-sigma * t) + scene.sun->irradiance_w_m2[k] * sun +
                                lamp.intensity_w_sr[k] * point;
        worst = std::max(worst, std::abs(o[k] - expected) / expected);
      }
      ++checked;
    }
  EXPECT_GT(checked, 200);
  EXPECT_GT(clear, 200);
  // The opacity builds up within the first slab behind the face (~0.02 m): e^{-0.4 * 0.02} ~ 1 %.
  // Measured 0.43 %.
  EXPECT_LT(worst, 0.01) << "largest relative error against the closed forms";
}

}  // namespace
}  // namespace nimbus::render
