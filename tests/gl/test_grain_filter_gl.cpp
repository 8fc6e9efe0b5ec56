// A still converges (grain_filter.hpp): one grainy jittered frame, filtered, lies within a
// stated bound of the mean of many jittered frames, nearer than unfiltered, with a hard-edged
// cloud's silhouette where the mean has it; a frame with little grain is left as it is.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nimbus/render/sky/grain_filter.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/frame/sky_renderer.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"
#include "test_small_sky.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

// The small sky, near and lit through few of its slices' depths, has little grain even on 16
// slices (measured, llvmpipe, 192x108: the printed lines; what parts its frame from the mean of
// 32 progressive samples is mostly the sub-pixel detail that only more samples give). The filter
// sees no grain there and leaves the picture as it is: it must not blur detail it cannot restore.
TEST(GrainFilterGl, AStillWithLittleGrainIsLeftAsItIs) {
  NIMBUS_REQUIRE_GL();
  const int w = 192, h = 108;
  for (const int slices : {128, 16}) {
    ViewState s = test::small_sky_still_state();
    ASSERT_TRUE(s.grain_filter.on);  // the default
    s.slices.slices = slices;
    SkyRenderer sky(s);
    ProgressiveFrame converged;
    for (unsigned i = 0; i < 32; ++i) {
      FrameQuality q;
      q.sample = progressive_sample(i);
      converged.add(sky.render(s, w, h, q, true), "converged");
    }
    PixelDepths depths;
    ProgressiveFrame one;
    one.add(sky.render(s, w, h, FrameQuality{}, true, nullptr, nullptr, &depths), "one");
    const Image still = still_picture(one.mean(), one.samples(), depths, s.grain_filter, s.slices.jitter);
    const double filtered = compare_images(still, converged.mean()).rel_rmse;
    const double raw = compare_images(one.mean(), converged.mean()).rel_rmse;
    std::printf("[ still, %d slices ] from the mean of 32 jittered frames: one frame %.2f %%, filtered %.2f %%\n", slices,
                100.0 * raw, 100.0 * filtered);
    EXPECT_LT(filtered, raw + 0.001) << slices << " slices";
  }
}

// Where alpha crosses a half along row y, from the left, linear between pixel centres (-1: it
// does not).
double left_crossing(const Image& img, int y) {
  for (int x = 0; x + 1 < img.width; ++x) {
    const double a = img.pixel(x, y)[3], b = img.pixel(x + 1, y)[3];
    if (a < 0.5 && b >= 0.5) return x + (0.5 - a) / (b - a);
  }
  return -1.0;
}
double right_crossing(const Image& img, int y) {
  for (int x = img.width - 1; x > 0; --x) {
    const double a = img.pixel(x, y)[3], b = img.pixel(x - 1, y)[3];
    if (a < 0.5 && b >= 0.5) return x - (0.5 - a) / (b - a);
  }
  return -1.0;
}

// A ball of uniform medium (a hard edge, softened only by the texture's trilinear filter; optical
// depth 2.4 across) on 12 slices: a grainy frame. Filtered, it lies nearer the converged mean
// (of 32 jittered frames; measured 4.45 % -> 2.34 %), and its silhouette (alpha = 1/2 along
// every row across the ball's middle) within a pixel of the mean's.
TEST(GrainFilterGl, AGrainyStillConvergesAndAHardEdgeStays) {
  NIMBUS_REQUIRE_GL();
  constexpr int kN = 24;
  const auto ball = [](int i, int j, int k) {
    const double c = 0.5 * (kN - 1);
    return std::hypot(i - c, j - c, k - c) < 0.4 * kN ? 1.0f : 0.0f;
  };
  CloudRenderer r({cube_cloud(kN, 1.0 / kN, ball, grey_optics(3.0))}, GL_R32F);
  const Camera cam = look_at_origin({0.0, 0.6, 3.0}, 128, 30.0);
  Light sun;
  sun.direction_to_sun = glm::normalize(glm::dvec3(0.4, 1.0, 0.3));
  CloudSliceSettings s;
  s.slices = 12;
  s.light_res = 64;
  ProgressiveFrame converged;
  for (unsigned i = 0; i < 32; ++i) {
    s.frame = i;
    converged.add(r.render(cam, sun, s), "converged");
  }
  s.frame = 0;
  const Image one = r.render(cam, sun, s);
  const Image filtered = filter_grain(one, PixelDepths{}, GrainFilter{});  // clouds alone: no depths
  // The rows whose chord is at least 0.85 of the widest: the silhouette crosses them at 58
  // degrees or steeper, so a move along a row is within 1.2 times the move across the edge
  // (near the top, a row grazes the edge and a tenth of a pixel across it is pixels along it).
  double widest = 0.0;
  for (int y = 0; y < cam.height; ++y)
    widest = std::max(widest, right_crossing(converged.mean(), y) - left_crossing(converged.mean(), y));
  double worst = 0.0, worst_raw = 0.0;
  int rows = 0;
  for (int y = 0; y < cam.height; ++y) {
    const double l = left_crossing(converged.mean(), y), rr = right_crossing(converged.mean(), y);
    if (l < 0.0 || rr < 0.0 || rr - l < 0.85 * widest) continue;
    ++rows;
    worst = std::max({worst, std::abs(left_crossing(filtered, y) - l), std::abs(right_crossing(filtered, y) - rr)});
    worst_raw = std::max({worst_raw, std::abs(left_crossing(one, y) - l), std::abs(right_crossing(one, y) - rr)});
  }
  std::printf("[ silhouette ] %d rows: farthest from the converged mean's, filtered %.2f px, unfiltered %.2f px\n",
              rows, worst, worst_raw);
  // and the filter did act: the frame's grain is less.
  const double grain_raw = compare_images(one, converged.mean()).rel_rmse;
  const double grain_filtered = compare_images(filtered, converged.mean()).rel_rmse;
  std::printf("[ silhouette ] the frame from the converged mean: %.2f %% unfiltered, %.2f %% filtered\n", 100.0 * grain_raw,
              100.0 * grain_filtered);
  EXPECT_GT(rows, 20);
  EXPECT_LE(worst, 1.0);
  EXPECT_LT(grain_filtered, 0.03);
  EXPECT_LT(grain_filtered, 0.7 * grain_raw);
}

}  // namespace
}  // namespace nimbus::render
