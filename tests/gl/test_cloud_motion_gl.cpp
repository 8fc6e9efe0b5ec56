// The slicer's keyframe blend and wind motion (CloudRenderer::set_motion, lib/cloud_density.glsl):
// a blend of two keyframes against the CPU reference of the same blended density, and a motion
// offset against the cloud rebuilt at the moved place.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/clouds/cloud_shadow.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 24;
constexpr double kVoxel = 1.0 / kN;

// Two keyframes: the lumpy ball and a shifted, thinner one on the same box.
std::vector<CloudVolume> blended(double w) {
  const CloudOptics o = grey_optics(8.0, 0.9);
  CloudVolume a = cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o);
  const CloudVolume b =
      cube_cloud(kN, kVoxel, [](int i, int j, int k) { return 0.6f * lumpy_ball(std::min(i + 2, kN - 1), j, k); }, o);
  set_next_keyframe(a, b.box, w);
  return {a};
}

// Measured (llvmpipe): rel RMSE 0.2-0.3 % at w = 0.5; tolerance 1 %, as for one keyframe.
TEST(CloudMotionGl, BlendOfKeyframesMatchesReference) {
  NIMBUS_REQUIRE_GL();
  const Camera cam = look_at_origin({0.4, 0.3, 2.5}, 64, 30.0);
  Light light;
  light.direction_to_sun = glm::dvec3(0.5, 0.6, 0.8);
  CloudReferenceSettings rs;
  rs.view_step_voxels = 0.25;
  rs.shadow_step_voxels = 0.5;
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 128;
  CloudRenderer r(blended(0.0), GL_R32F);
  double far_apart = 0.0;
  for (double w : {0.0, 0.5, 1.0}) {
    r.set_motion({CloudMotion{glm::dvec3(0.0), w}});
    const Image img = r.render(cam, light, s);
    const Image ref = render_cloud_reference(blended(w), cam, light, rs);
    const ImageError e = compare_images(img, ref);
    std::printf("[ blend %.1f vs reference ] rel RMSE %.4f over %zu pixels\n", w, e.rel_rmse, e.pixels);
    EXPECT_GT(e.pixels, 1000u);
    EXPECT_LT(e.rel_rmse, 0.01) << "blend " << w;
    if (w == 1.0) far_apart = compare_images(img, render_cloud_reference(blended(0.0), cam, light, rs)).rel_rmse;
  }
  EXPECT_GT(far_apart, 0.05) << "the keyframes differ, so the blend was really tested";
}

// Measured (llvmpipe): identical images (the planes and maps move with the cloud exactly).
TEST(CloudMotionGl, MotionEqualsTheCloudBuiltAtTheMovedPlace) {
  NIMBUS_REQUIRE_GL();
  const CloudOptics o = grey_optics(8.0, 0.9);
  const glm::dvec3 offset(0.3125, -0.125, 0.25);
  const CloudVolume here = cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o);
  const CloudVolume there =
      cube_cloud(kN, kVoxel, [](int i, int j, int k) { return lumpy_ball(i, j, k); }, o, offset);
  const Camera cam = look_at_origin({0.6, 0.5, 2.8}, 64, 40.0);
  Light light;
  light.direction_to_sun = glm::dvec3(-0.3, 0.6, 0.7);
  CloudSliceSettings s;
  s.slices = 48;
  s.light_res = 128;
  CloudRenderer moved({here}, GL_R32F);
  moved.set_motion({CloudMotion{offset, 0.0}});
  CloudRenderer built({there}, GL_R32F);
  const Image a = moved.render(cam, light, s), b = built.render(cam, light, s);
  double worst = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    worst = std::max(worst, std::abs(double(a.rgba[i]) - b.rgba[i]));
    sum += b.rgba[i];
  }
  EXPECT_GT(sum, 10.0);
  EXPECT_LT(worst, 1e-4) << "moving by set_motion must equal building the cloud there";
  // Moving back to 0 restores the unmoved cloud exactly (motion is from the placement, not cumulative).
  moved.set_motion({CloudMotion{glm::dvec3(5.0, 0.0, 0.0), 0.0}});
  moved.set_motion({CloudMotion{glm::dvec3(0.0), 0.0}});
  CloudRenderer still({here}, GL_R32F);
  const Image c = moved.render(cam, light, s), d = still.render(cam, light, s);
  EXPECT_EQ(c.rgba, d.rgba);
  EXPECT_THROW(moved.set_motion({}), std::invalid_argument);
  EXPECT_THROW(moved.set_motion({CloudMotion{glm::dvec3(0.0), 0.5}}), std::invalid_argument) << "no next keyframe";
}

}  // namespace
}  // namespace nimbus::render
