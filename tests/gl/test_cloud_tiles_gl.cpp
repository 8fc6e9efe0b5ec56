// A periodic tile drawn to the horizon by the slicer (render/core cloud_tiles.hpp): an endless
// homogeneous slab made of one tile has the closed-form alpha across every seam and the split
// between the near and far passes, out to its reach (and without copies it ends at the tile); a
// lumpy tile's copies look as the same copies uploaded one by one and drawn in one pass.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

constexpr int kN = 16;
constexpr double kVoxel = 1.0 / kN;  // a 1 m tile: period 1 m along x and z

CloudVolume periodic_tile(const std::function<float(int, int, int)>& density, double sigma) {
  CloudVolume c = cube_cloud(kN, kVoxel, density, grey_optics(sigma));
  c.period_m = glm::dvec3(1.0, 0.0, 1.0);
  return c;
}

// The eye 1 m under the slab's lower face (y -0.5), looking toward -z and up, as at the sky.
Camera under_the_layer() {
  Camera c;
  c.eye = glm::dvec3(0.3, -1.5, 0.2);
  c.look_at = glm::dvec3(0.3, 0.5, -4.0);
  c.fov_deg = 80.0;
  c.width = 96;
  c.height = 64;
  c.near_m = 0.01;
  c.far_m = 100.0;
  return c;
}

Light sun() {
  Light l;
  l.direction_to_sun = glm::normalize(glm::dvec3(0.3, 1.0, 0.4));
  return l;
}

// Rays through the slab (its plateau |y| <= 0.5 - h/2 and the voxel of ramp beyond each face) that
// leave it within `reach` less a tile's diagonal: every copy they cross is drawn.
TEST(CloudTiles, AnEndlessSlabHasTheClosedFormAlphaAcrossEverySeamToItsReach) {
  NIMBUS_REQUIRE_GL();
  const double sigma = 0.7, reach = 8.0;
  CloudRenderer r({periodic_tile([](int, int, int) { return 1.0f; }, sigma)}, GL_R32F);
  const Camera cam = under_the_layer();
  CloudSliceSettings s;
  s.slices = 64;
  s.light_res = 64;
  s.jitter = false;
  s.repeat_to_m = reach;
  const Image tiled = r.render(cam, sun(), s);
  s.repeat_to_m = 0.0;
  const Image one = r.render(cam, sun(), s);
  ASSERT_TRUE(all_finite(tiled));
  const double top = 0.5 * kN * kVoxel + kVoxel;  // the ramp's end above the upper face
  int checked = 0, ends = 0;
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 d = pixel_ray(cam, x, y);
      if (d.y < 0.05) continue;
      const glm::dvec3 out = cam.eye + d * ((top - cam.eye.y) / d.y);
      if (std::hypot(out.x - cam.eye.x, out.z - cam.eye.z) > reach - 1.5) continue;
      // Optical depth sigma x (thickness n h) / |dir.y|: the ramps add what the plateau's edges lack.
      const double expected = 1.0 - std::exp(-sigma * kN * kVoxel / d.y);
      worst = std::max(worst, std::abs(tiled.pixel(x, y)[3] - expected));
      ++checked;
      ends += std::abs(one.pixel(x, y)[3] - expected) > 0.1;
    }
  EXPECT_GT(checked, 1500);
  // Measured 5.1e-3, at the far pass's thicker slabs through the slab's one-voxel ramps (one tile
  // alone: 0.8 on most of these pixels).
  EXPECT_LT(worst, 1e-2) << "largest |alpha - closed form| over " << checked << " pixels";
  EXPECT_GT(ends, checked / 2) << "one tile alone should end where its copies go on";
  EXPECT_NE(tiled.metadata.at("periodic_copies").find("far"), std::string::npos);
}

// A lumpy tile, periodic in i and k, thinning to nothing at its top and bottom.
float lumpy_periodic(int i, int j, int k) {
  const double a = 2.0 * M_PI * i / kN, b = 2.0 * M_PI * k / kN;
  const double h = (j - 0.5 * (kN - 1)) / (0.5 * kN);
  const double v = 0.55 + 0.35 * std::sin(a + 0.4) * std::cos(2.0 * b) + 0.25 * std::sin(2.0 * a + b);
  return static_cast<float>(std::clamp(v * (1.0 - h * h) * 1.6 - 0.3, 0.0, 1.0));
}

TEST(CloudTiles, CopiesLookAsTheSameCopiesUploadedAndDrawnInOnePass) {
  NIMBUS_REQUIRE_GL();
  const double reach = 6.0;
  const CloudVolume base = periodic_tile(lumpy_periodic, 6.0);
  const Camera cam = under_the_layer();
  CloudSliceSettings s;
  s.slices = 128;
  s.light_res = 256;
  s.jitter = false;
  s.repeat_to_m = reach;
  CloudRenderer tiled_renderer({base}, GL_R32F);
  const Image tiled = tiled_renderer.render(cam, sun(), s);
  // The same copies, one cloud each: those whose box comes within reach of the eye in x and z.
  std::vector<CloudVolume> copies;
  for (int a = -8; a <= 8; ++a)
    for (int b = -8; b <= 8; ++b) {
      CloudVolume c = base;
      c.period_m = glm::dvec3(0.0);
      translate(c, glm::dvec3(a, 0.0, b));
      const double dx = std::max({c.world_min.x - cam.eye.x, 0.0, cam.eye.x - c.world_max.x});
      const double dz = std::max({c.world_min.z - cam.eye.z, 0.0, cam.eye.z - c.world_max.z});
      if (std::hypot(dx, dz) <= reach) copies.push_back(std::move(c));
    }
  CloudRenderer copies_renderer(copies, GL_R32F);
  s.repeat_to_m = 0.0;
  s.slices = 1024;  // one pass over every copy, its slab as thin as the tiles' near pass's
  s.light_res = 1024;
  const Image uploaded = copies_renderer.render(cam, sun(), s);
  double sum = 0.0, mean = 0.0, alpha = 0.0;
  int n = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      for (int ch = 0; ch < 3; ++ch) {
        const double d = tiled.pixel(x, y)[ch] - uploaded.pixel(x, y)[ch];
        sum += d * d;
        mean += uploaded.pixel(x, y)[ch];
        ++n;
      }
      alpha = std::max(alpha, static_cast<double>(std::abs(tiled.pixel(x, y)[3] - uploaded.pixel(x, y)[3])));
    }
  mean /= n;
  const double rel = std::sqrt(sum / n) / mean;
  ASSERT_GT(mean, 0.0);
  std::printf("copies: RMS RGB difference %.4f of the mean, largest alpha difference %.4f\n", rel, alpha);
  // Measured 0.029 and 0.014: the far pass's thicker slabs and its own light buffer.
  EXPECT_LT(rel, 0.05);
  EXPECT_LT(alpha, 0.02);
}

}  // namespace
}  // namespace nimbus::render
