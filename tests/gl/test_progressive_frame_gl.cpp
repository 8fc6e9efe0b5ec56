// A still view's progressive samples through the sky renderer (progressive_frame.hpp): a
// sample's sub-pixel offset moves every pass of the frame alike (sky, ground, clouds, shafts),
// and the mean of the samples converges to the supersampled frame, losing the grain of the
// slicer's jitter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/render/frame/sky_renderer.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "test_gl_support.hpp"
#include "test_small_sky.hpp"

namespace nimbus::render {
namespace {

ViewState small_sky() { return test::small_sky_still_state(); }

// `a` moved by (dx, dy) pixels against `b`, over the pixels both hold: rel RMSE of a(x, y)
// against b(x + dx, y + dy).
double shifted_rel_rmse(const Image& a, const Image& b, int dx, int dy) {
  double num = 0.0, den = 0.0;
  for (int y = 1; y + 1 < a.height; ++y)
    for (int x = 1; x + 1 < a.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double r = b.pixel(x + dx, y + dy)[c];
        num += (a.pixel(x, y)[c] - r) * (a.pixel(x, y)[c] - r);
        den += r * r;
      }
  return std::sqrt(num / den);
}

// A whole pixel of offset is the frame moved by a pixel: every pass (the sky and the clouds'
// composite, which cast rays per pixel; the ground and the slices, which are rasterised) moves
// the same way, with x right and y down as Camera::pixel_offset says.
TEST(ProgressiveFrameGl, APixelOfOffsetMovesEveryPassByAPixel) {
  NIMBUS_REQUIRE_GL();
  const int w = 160, h = 90;
  ViewState s = small_sky();
  s.slices.jitter = false;  // the jitter tile is fixed to the pixels, not to the rays
  SkyRenderer sky(s);
  const Image plain = sky.render(s, w, h, FrameQuality{}, true);
  for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
    FrameQuality q;
    q.sample.pixel_offset = glm::dvec2(dx, dy);
    const Image moved = sky.render(s, w, h, q, true);
    const double aligned = shifted_rel_rmse(moved, plain, dx, dy);
    const double unaligned = shifted_rel_rmse(moved, plain, 0, 0);
    const double wrong_way = shifted_rel_rmse(moved, plain, -dx, -dy);
    std::printf("[ offset (%d, %d) ] against the plain frame moved by it %.2e, unmoved %.2e, moved the other way %.2e\n", dx,
                dy, aligned, unaligned, wrong_way);
    EXPECT_LT(aligned, 2e-3);
    EXPECT_GT(unaligned, 5.0 * aligned);
    EXPECT_GT(wrong_way, 5.0 * aligned);
  }
}

// Measured (llvmpipe, 160x90, 128 slices): see the printed lines. The reference is 4x
// supersampled (a 320x180 frame, 2x2 boxes) and itself the mean of 16 samples, so its own grain
// is below the tolerance.
TEST(ProgressiveFrameGl, AStillViewConvergesToTheSupersampledFrame) {
  NIMBUS_REQUIRE_GL();
  const int w = 160, h = 90;
  const ViewState s = small_sky();
  SkyRenderer sky(s);
  ProgressiveFrame fine;
  for (unsigned i = 0; i < 16; ++i) {
    FrameQuality q;
    q.sample = progressive_sample(i);
    fine.add(sky.render(s, 2 * w, 2 * h, q, true), "fine");
  }
  const Image reference = box_downsample(fine.mean(), 2);
  ProgressiveFrame mean;
  double plain_error = 0.0, last_error = 0.0;
  for (unsigned i = 0; i < 64; ++i) {
    FrameQuality q;
    q.sample = progressive_sample(i);
    const Image frame = sky.render(s, w, h, q, true);
    check_image(frame, "sample");
    mean.add(frame, "coarse");
    if (i == 0 || i == 3 || i == 15 || i == 63) {
      const ImageError e = compare_images(mean.mean(), reference);
      std::printf("[ %2u samples ] rel RMSE to the 4x-supersampled frame %.4f (median %.4f) over %zu pixels\n", i + 1,
                  e.rel_rmse, e.median_rel, e.pixels);
      if (i == 0) plain_error = e.rel_rmse;
      last_error = e.rel_rmse;
    }
  }
  EXPECT_LT(last_error, 0.01);
  EXPECT_GT(plain_error, 2.0 * last_error) << "the plain frame's grain and aliasing should be what the samples remove";
}

// A resize, a sun jump and a new sample restart the mean, and nothing that reaches a frame or the
// mean is NaN or Inf (check_image throws on either, so add() would refuse the frame).
TEST(ProgressiveFrameGl, AResizeOrASunJumpStartsAFiniteMeanAgain) {
  NIMBUS_REQUIRE_GL();
  ViewState s = small_sky();
  SkyRenderer sky(s);
  ProgressiveFrame mean;
  const auto key = [](const ViewState& v, int w, int h) {
    return view_state_to_json(v).dump() + " " + std::to_string(w) + "x" + std::to_string(h);
  };
  struct Step {
    int w, h;
    double sun_elevation_deg;
    unsigned samples;
  };
  for (const Step& step : {Step{160, 90, 35.0, 3}, Step{97, 53, 35.0, 2}, Step{97, 53, 2.0, 2}, Step{160, 90, 85.0, 2}}) {
    s.sky.sun_elevation_deg = step.sun_elevation_deg;
    for (unsigned i = 0; i < step.samples; ++i) {
      FrameQuality q;
      q.sample = progressive_sample(i);
      const Image frame = sky.render(s, step.w, step.h, q, true);
      EXPECT_NO_THROW(check_image(frame, "frame")) << step.w << "x" << step.h << " sun " << step.sun_elevation_deg;
      mean.add(frame, key(s, step.w, step.h));
    }
    EXPECT_EQ(mean.samples(), step.samples) << "a new size or sun starts a new mean";
    EXPECT_EQ(mean.mean().width, step.w);
    EXPECT_NO_THROW(check_image(mean.mean(), "mean"));
  }
}

}  // namespace
}  // namespace nimbus::render
