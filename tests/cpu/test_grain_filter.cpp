// The still's grain filter (grain_filter.hpp) on made-up frames: blue-noise grain over a
// constant goes, a constant stays exact, a straight edge stays where it was, surfaces are neither
// filtered nor taken, a cloud far behind a near one is not taken, and bad input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "nimbus/render/core/blue_noise.hpp"
#include "nimbus/render/sky/grain_filter.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"

namespace nimbus::render {
namespace {

constexpr int kW = 96, kH = 64;

// Depths with every pixel on clouds at `metres`.
PixelDepths cloud_depths(int w, int h, float metres) {
  PixelDepths d;
  d.width = w;
  d.height = h;
  d.values.assign(static_cast<std::size_t>(w) * h * 2, 0.0f);
  for (std::size_t i = 0; i < d.values.size(); i += 2) {
    d.values[i] = metres;
    d.values[i + 1] = 1.0f;
  }
  return d;
}

void set_depth(PixelDepths& d, int x, int y, float metres, bool clouds) {
  d.values[2 * (static_cast<std::size_t>(y) * d.width + x)] = metres;
  d.values[2 * (static_cast<std::size_t>(y) * d.width + x) + 1] = clouds ? 1.0f : 0.0f;
}

// A grey frame of `level` plus `amplitude` times the slicer's kind of grain: a 64^2 blue-noise
// tile's values less a half.
Image grainy_frame(double level, double amplitude) {
  const std::vector<float> tile = blue_noise_tile(64, 5);
  Image img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const double v = level + amplitude * (tile[(y % 64) * 64 + (x % 64)] - 0.5);
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = static_cast<float>(v);
      img.pixel(x, y)[3] = 1.0f;
    }
  return img;
}

double rms_about(const Image& img, double level, int margin) {
  double sum = 0.0;
  int n = 0;
  for (int y = margin; y < img.height - margin; ++y)
    for (int x = margin; x < img.width - margin; ++x) {
      const double e = img.pixel(x, y)[0] - level;
      sum += e * e;
      ++n;
    }
  return std::sqrt(sum / n);
}

// Blue noise's energy lies at high spatial frequencies: the filter takes most of it. Measured:
// the grain's RMS falls about 20-fold at 1 px; the bound is 8-fold.
TEST(GrainFilter, BlueNoiseGrainOverAConstantGoes) {
  const Image grainy = grainy_frame(1.0, 0.4);
  const Image filtered = filter_grain(grainy, cloud_depths(kW, kH, 2000.0f), GrainFilter{});
  const double before = rms_about(grainy, 1.0, 3), after = rms_about(filtered, 1.0, 3);
  std::printf("[ grain ] RMS %.4f -> %.4f (%.1fx less)\n", before, after, before / after);
  EXPECT_GT(before, 0.1);
  EXPECT_LT(after, before / 8.0);
}

// A constant frame is a fixed point (the weights are normalised), to float rounding, alpha too.
TEST(GrainFilter, AConstantFrameIsUnchanged) {
  Image flat = grainy_frame(0.37, 0.0);
  const Image out = filter_grain(flat, cloud_depths(kW, kH, 500.0f), GrainFilter{});
  for (std::size_t i = 0; i < flat.rgba.size(); ++i) ASSERT_NEAR(out.rgba[i], flat.rgba[i], 1e-6f) << "value " << i;
  EXPECT_EQ(out.metadata.count("grain_filter"), 1u);
}

// A straight edge between two levels keeps its half-way point where it was: the kernel is
// symmetric. Rows cross a vertical edge at x = 40 (0 to its left, 1 from it).
TEST(GrainFilter, AStraightEdgeStaysWhereItWas) {
  Image img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float v = x >= 40 ? 1.0f : 0.0f;
      for (int c = 0; c < 4; ++c) img.pixel(x, y)[c] = v;
    }
  const Image out = filter_grain(img, PixelDepths{}, GrainFilter{});  // clouds alone: alpha is filtered too
  for (int y = 0; y < kH; ++y) {
    // The crossing of 0.5, linear between pixel centres; the unfiltered edge's is at 39.5.
    double crossing = -1.0;
    for (int x = 0; x + 1 < kW; ++x) {
      const double a = out.pixel(x, y)[3], b = out.pixel(x + 1, y)[3];
      if (a < 0.5 && b >= 0.5) crossing = x + (0.5 - a) / (b - a);
    }
    ASSERT_NEAR(crossing, 39.5, 1e-3) << "row " << y;
    EXPECT_LT(out.pixel(37, y)[3], 0.05f);  // and it is no wider than a few pixels
    EXPECT_GT(out.pixel(42, y)[3], 0.95f);
  }
}

// The ground carries no grain: its pixels stay as they were, and the clouds beside it do not
// take its light.
TEST(GrainFilter, SurfacesAreNeitherFilteredNorTaken) {
  Image img = grainy_frame(1.0, 0.4);
  PixelDepths d = cloud_depths(kW, kH, 3000.0f);
  for (int y = kH / 2; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      set_depth(d, x, y, 800.0f, false);  // the ground, bright
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = 50.0f + (x % 3);
    }
  const Image out = filter_grain(img, d, GrainFilter{});
  for (int y = kH / 2; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ASSERT_EQ(out.pixel(x, y)[0], img.pixel(x, y)[0]) << x << "," << y;
  // The clouds' row next to the ground: its grain averaged, none of the ground's 50.
  for (int x = 3; x < kW - 3; ++x) {
    EXPECT_GT(out.pixel(x, kH / 2 - 1)[0], 0.8f) << x;
    EXPECT_LT(out.pixel(x, kH / 2 - 1)[0], 1.2f) << x;
  }
}

// A cloud 10 times farther than the near one it borders gives it little: at the default
// tolerance (1.0) its weight is 1 / (1 + 9^2). Both carry grain stronger than the step between
// them, so the filter acts across the border; the near cloud's column by it, averaged down the
// rows, stays within a per cent of its own level (1), where a filter blind to depth takes in
// the far one's (1.5).
TEST(GrainFilter, AFarCloudIsNotTakenIntoANearOne) {
  Image img = grainy_frame(1.0, 0.4);
  PixelDepths d = cloud_depths(kW, kH, 1000.0f);
  for (int y = 0; y < kH; ++y)
    for (int x = kW / 2; x < kW; ++x) {
      set_depth(d, x, y, 10000.0f, true);
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] += 0.5f;
    }
  const Image aware = filter_grain(img, d, GrainFilter{});
  const Image blind = filter_grain(img, PixelDepths{}, GrainFilter{});
  double near_edge = 0.0, blind_edge = 0.0;
  for (int y = 0; y < kH; ++y) {
    near_edge += aware.pixel(kW / 2 - 1, y)[0] / kH;
    blind_edge += blind.pixel(kW / 2 - 1, y)[0] / kH;
  }
  std::printf("[ depth ] the near cloud's edge column: %.3f with depths, %.3f without (its own 1, the far one's 1.5)\n",
              near_edge, blind_edge);
  EXPECT_LT(std::abs(near_edge - 1.0), 0.01);
  EXPECT_GT(blind_edge, 1.05);
}

// A cloud pixel whose few samples fell on the clouds far behind reads their distance (the
// distance is an alpha-weighted mean of grainy samples) and shows as a dark dot. Weighed against
// its neighbours by its own distance it would take nothing from them and keep the dot; against
// the median distance of its 3x3 neighbourhood it is filtered like them.
TEST(GrainFilter, ADotThatReadTheFarCloudsIsFilteredWithItsNeighbours) {
  Image img = grainy_frame(1.0, 0.4);
  PixelDepths d = cloud_depths(kW, kH, 1000.0f);
  int dots = 0;
  for (int y = 8; y < kH - 8; y += 9)
    for (int x = 8; x < kW - 8; x += 9) {
      set_depth(d, x, y, 10000.0f, true);
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = 0.2f;
      ++dots;
    }
  const Image out = filter_grain(img, d, GrainFilter{});
  double worst = 1.0;
  for (int y = 8; y < kH - 8; y += 9)
    for (int x = 8; x < kW - 8; x += 9) worst = std::min(worst, static_cast<double>(out.pixel(x, y)[0]));
  std::printf("[ dots ] %d dots of 0.2 in clouds of 1: the darkest after the filter %.3f\n", dots, worst);
  EXPECT_GT(worst, 0.75);
}

// Huge, tiny and zero values stay finite and non-negative.
TEST(GrainFilter, ExtremeValuesStayFinite) {
  Image img = grainy_frame(0.0, 0.0);
  img.pixel(10, 10)[0] = 3.0e38f;
  img.pixel(11, 10)[1] = 1.0e-38f;
  const Image out = filter_grain(img, cloud_depths(kW, kH, 1.0e-3f), GrainFilter{});
  for (float v : out.rgba) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
}

TEST(GrainFilter, BadInputIsRefused) {
  const Image img = grainy_frame(1.0, 0.1);
  EXPECT_THROW(filter_grain(img, cloud_depths(kW + 1, kH, 100.0f), GrainFilter{}), std::invalid_argument);
  for (double sigma : {0.0, -1.0, 5.0, std::nan("")}) {
    GrainFilter f;
    f.sigma_px = sigma;
    EXPECT_THROW(validate(f), std::invalid_argument) << sigma;
  }
  GrainFilter f;
  f.depth_tolerance = 0.0;
  EXPECT_THROW(validate(f), std::invalid_argument);
  f = GrainFilter{};
  f.off_from_samples = 0;
  EXPECT_THROW(validate(f), std::invalid_argument);
}

// On for a still of few jittered frames, narrower as they add up, and off without jitter, when
// switched off or from off_from_samples on.
TEST(GrainFilter, AppliesToFewJitteredFramesAndNarrowsAsTheyAddUp) {
  const GrainFilter f;
  EXPECT_TRUE(grain_filter_applies(f, 1, true));
  EXPECT_TRUE(grain_filter_applies(f, f.off_from_samples - 1, true));
  EXPECT_FALSE(grain_filter_applies(f, f.off_from_samples, true));
  EXPECT_FALSE(grain_filter_applies(f, 1, false));
  GrainFilter off;
  off.on = false;
  EXPECT_FALSE(grain_filter_applies(off, 1, true));
  EXPECT_DOUBLE_EQ(grain_filter_sigma_px(f, 1), f.sigma_px);
  EXPECT_NEAR(grain_filter_sigma_px(f, 4), 0.8 * f.sigma_px, 1e-12);
  EXPECT_NEAR(grain_filter_sigma_px(f, 1024), 0.6 * f.sigma_px, 1e-12);
  // The still's picture: its mean filtered for one frame, the mean itself without jitter.
  ProgressiveFrame mean;
  mean.add(grainy_frame(1.0, 0.4), "still");
  const PixelDepths d = cloud_depths(kW, kH, 700.0f);
  EXPECT_LT(rms_about(still_picture(mean.mean(), mean.samples(), d, f, true), 1.0, 3), rms_about(mean.mean(), 1.0, 3) / 8.0);
  EXPECT_EQ(still_picture(mean.mean(), mean.samples(), d, f, false).rgba, mean.mean().rgba);
}

}  // namespace
}  // namespace nimbus::render
