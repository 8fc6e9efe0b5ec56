// The surface airlight on the GPU (shaders/surface.frag.glsl with lib/surface_airlight_texture.glsl)
// against the CPU reference's same term, on a ground plane and a box under one lamp: the term
// alone, isolated as the image with it minus the image without it in each renderer (so the
// shafts, shadows and everything else cancel), attenuated by e^(-Tvp) like any surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"

namespace nimbus::render {
namespace {

class SurfaceAirlightGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      gl_ = GlContext::create_headless().release();
    } catch (const GlUnavailable& e) {
      skip_reason_ = e.what();
    }
  }
  static void TearDownTestSuite() {
    delete gl_;
    gl_ = nullptr;
  }
  void SetUp() override {
    if (!gl_) GTEST_SKIP() << "no OpenGL context: " << skip_reason_;
    gl_->make_current();
  }
  static inline GlContext* gl_ = nullptr;
  static inline std::string skip_reason_;
};

// A ground plane and a box under one lamp in thick isotropic fog (Tsp from 0.4 to ~6 over the view),
// seen from above so that every pixel is a surface: the box's sides facing away from the lamp
// are lit by nothing but the airlight.
Scene lamp_over_ground() {
  Scene s;
  s.name = "surface-airlight-test";
  s.medium.extinction_per_m = 0.35;
  s.medium.albedo = 0.9;
  s.ground = GroundPlane{};
  s.ground->material.albedo = glm::dvec3(0.7, 0.5, 0.3);
  Box b;
  b.min_m = glm::dvec3(1.5, 0.0, -1.0);
  b.max_m = glm::dvec3(3.0, 1.2, 0.5);
  b.material.albedo = glm::dvec3(0.4, 0.6, 0.8);
  s.boxes.push_back(b);
  s.lamps.push_back(point_light(glm::dvec3(0.0, 1.2, 0.0), glm::dvec3(300.0, 250.0, 200.0)));
  s.camera.eye = glm::dvec3(-1.0, 7.0, 6.0);
  s.camera.look_at = glm::dvec3(1.0, 0.0, 0.0);
  s.camera.fov_deg = 70.0;
  s.camera.width = 96;
  s.camera.height = 64;
  return s;
}

// The surface term in one renderer: (with) - (without), per pixel and channel.
std::vector<double> difference(const Image& with, const Image& without) {
  std::vector<double> d(with.rgba.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = double(with.rgba[i]) - double(without.rgba[i]);
  return d;
}

TEST_F(SurfaceAirlightGl, GpuTermMatchesTheReferenceTerm) {
  const Scene scene = lamp_over_ground();
  ReferenceSettings rs;
  rs.threads = 2;
  const Image ref_on = render_reference(scene, scene.camera, rs);
  rs.surface_airlight = false;
  const Image ref_off = render_reference(scene, scene.camera, rs);
  EXPECT_EQ(ref_on.metadata.at("surface_airlight"), "on");

  ShaftSettings on, off;
  off.surface_airlight = false;
  const ShaftMethod method = parse_shaft_method("analytic");
  ShaftRenderer gpu_on(scene, on), gpu_off(scene, off);
  const Image img_on = gpu_on.render(scene.camera, method);
  const Image img_off = gpu_off.render(scene.camera, method);
  for (float v : img_on.rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);

  const std::vector<double> ref = difference(ref_on, ref_off), gpu = difference(img_on, img_off);
  // Per pixel (RGB), relative to the reference term; pixels whose surface differs between the
  // rasteriser and the exact ray (the box's silhouette) are the only large ones.
  std::vector<double> rel;
  double sum_d2 = 0.0, sum_r2 = 0.0, smallest_ref = 1e300;
  for (std::size_t p = 0; p < ref.size() / 4; ++p) {
    for (int c = 0; c < 3; ++c) {
      const double r = ref[4 * p + c], g = gpu[4 * p + c];
      smallest_ref = std::min(smallest_ref, r);
      rel.push_back(std::abs(g - r) / r);
      sum_d2 += (g - r) * (g - r);
      sum_r2 += r * r;
    }
  }
  // Every surface point receives airlight, whichever way it faces (the box's far sides too).
  EXPECT_GT(smallest_ref, 0.0);
  std::sort(rel.begin(), rel.end());
  const double median = rel[rel.size() / 2], p98 = rel[rel.size() * 98 / 100];
  const double rmse = std::sqrt(sum_d2 / sum_r2);
  std::printf("surface airlight GPU vs reference term: rel. RMSE %.2e, median %.2e, 98th percentile %.2e, max %.2e\n",
              rmse, median, p98, rel.back());
  EXPECT_LT(median, 1e-3);
  EXPECT_LT(p98, 5e-3);
  EXPECT_LT(rmse, 1e-2);
}

TEST_F(SurfaceAirlightGl, TermBrightensTheSideFacingAwayFromTheLamp) {
  // The box's face at x = 3 looks away from the lamp: without the term only the fog's glow in
  // front of it lights its pixel; with it, the surface itself brightens.
  Scene scene = lamp_over_ground();
  scene.camera.eye = glm::dvec3(6.0, 0.6, -0.25);
  scene.camera.look_at = glm::dvec3(3.0, 0.6, -0.25);
  scene.camera.fov_deg = 20.0;
  scene.camera.width = scene.camera.height = 8;
  ShaftSettings on, off;
  off.surface_airlight = false;
  const ShaftMethod method = parse_shaft_method("analytic");
  ShaftRenderer gpu_on(scene, on), gpu_off(scene, off);
  const Image a = gpu_on.render(scene.camera, method), b = gpu_off.render(scene.camera, method);
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) EXPECT_GT(a.rgba[i + 1], b.rgba[i + 1] * 1.001f) << i / 4;
}

}  // namespace
}  // namespace nimbus::render
