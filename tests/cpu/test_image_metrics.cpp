// Image comparison over lit pixels: the mask as documented (quantile of positive luminance),
// known errors giving their closed-form numbers, unlit pixels ignored, all three colour
// channels counted, and refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "nimbus/render/image/image_metrics.hpp"

namespace {

using nimbus::render::compare_images;
using nimbus::render::ErrorMask;
using nimbus::render::Image;
using nimbus::render::lit_pixels;
using nimbus::render::noise_corrected_rel_rmse;

// 20 x 10: the top half a grey ramp 1, 2, ..., 100 (luminance = the grey value, since the
// luminance weights sum to 1), the bottom half black.
Image ramp() {
  Image im(20, 10);
  for (int i = 0; i < 100; ++i) {
    float* p = im.pixel(i % 20, i / 20);
    p[0] = p[1] = p[2] = static_cast<float>(i + 1);
    p[3] = 1.0f;
  }
  return im;
}

// Runs f, expecting std::invalid_argument whose message mentions `mentions`.
template <class F>
void expect_error(F&& f, const std::string& mentions) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << mentions;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

double sum_squares_from(int first, int last) {  // sum of v^2 for v = first .. last
  double s = 0.0;
  for (int v = first; v <= last; ++v) s += double(v) * v;
  return s;
}

TEST(ImageMetrics, MaskIsTheQuantileOfPositiveLuminanceTimesTheLitFraction) {
  // Positive luminances 1..100 (the 100 black pixels do not count): the 0.99 quantile is the
  // ceil(99)-th smallest = 99; lit means > 0.05 * 99 = 4.95, i.e. values 5..100: 96 pixels.
  const auto lit = lit_pixels(ramp(), {0.05, 0.01, 0.99});
  EXPECT_EQ(std::accumulate(lit.begin(), lit.end(), 0), 96);
  EXPECT_EQ(lit[3], 0);   // value 4
  EXPECT_EQ(lit[4], 1);   // value 5
  EXPECT_EQ(lit[150], 0); // black
  // The median (0.5 quantile: the 50th smallest = 50) with fraction 0.5: > 25, 75 pixels.
  const auto half = lit_pixels(ramp(), {0.5, 0.01, 0.5});
  EXPECT_EQ(std::accumulate(half.begin(), half.end(), 0), 75);
  // Defaults: > 1e-3 * 99: every non-black pixel.
  const auto all = lit_pixels(ramp());
  EXPECT_EQ(std::accumulate(all.begin(), all.end(), 0), 100);
}

// The median follows the typical pixel, not the worst: 10 of the 100 lit pixels 5x too bright
// and the rest 1 % too bright give a median of 1 % while the maximum is 4 (400 %).
TEST(ImageMetrics, MedianIgnoresAFewBadPixels) {
  const Image ref = ramp();
  Image test = ref;
  for (int i = 0; i < 100; ++i) {
    float* p = test.pixel(i % 20, i / 20);
    const float factor = i % 10 == 0 ? 5.0f : 1.01f;
    for (int c = 0; c < 3; ++c) p[c] *= factor;
  }
  const auto e = compare_images(test, ref);
  EXPECT_NEAR(e.median_rel, 0.01, 1e-6);
  EXPECT_NEAR(e.max_rel, 4.0, 1e-6);
}

TEST(ImageMetrics, IdenticalImagesHaveNoError) {
  const auto e = compare_images(ramp(), ramp());
  EXPECT_EQ(e.rel_rmse, 0.0);
  EXPECT_EQ(e.max_rel, 0.0);
  EXPECT_EQ(e.mean_bias, 0.0);
  EXPECT_EQ(e.median_rel, 0.0);
  EXPECT_EQ(e.pixels, 100u);
}

TEST(ImageMetrics, UniformScalingGivesItsFactorEverywhere) {
  Image t = ramp();
  for (float& v : t.rgba) v *= 1.03f;
  const auto e = compare_images(t, ramp());
  EXPECT_NEAR(e.rel_rmse, 0.03, 1e-6);
  EXPECT_NEAR(e.max_rel, 0.03, 1e-6);
  EXPECT_NEAR(e.mean_bias, 0.03, 1e-6);
  for (float& v : t.rgba) v *= 0.9f / 1.03f;
  EXPECT_NEAR(compare_images(t, ramp()).mean_bias, -0.1, 1e-6);
}

TEST(ImageMetrics, OnePixelErrorAndTheFloor) {
  // Mask {0.05, 0.1, 0.99}: lit values 5..100, P = 99, floor = 9.9.
  const ErrorMask mask{0.05, 0.1, 0.99};
  const double d = 2.0;
  for (const int value : {6, 50}) {
    Image t = ramp();
    t.pixel((value - 1) % 20, (value - 1) / 20)[1] += static_cast<float>(d);  // green only
    const auto e = compare_images(t, ramp(), mask);
    const double sum_ref_sq = 3.0 * sum_squares_from(5, 100);
    const double sum_ref = 3.0 * (5 + 100) * 96 / 2.0;
    EXPECT_EQ(e.pixels, 96u);
    EXPECT_NEAR(e.rel_rmse, std::sqrt(d * d / sum_ref_sq), 1e-12);
    EXPECT_NEAR(e.mean_bias, d / sum_ref, 1e-12);
    // Relative to max(r, floor): the floor keeps the dim pixel (6 < 9.9) from dominating.
    EXPECT_NEAR(e.max_rel, d / std::max(double(value), 9.9), 1e-12) << value;
  }
}

TEST(ImageMetrics, UnlitPixelsAndAlphaAreIgnoredButEveryColourChannelCounts) {
  Image t = ramp();
  t.pixel(5, 7)[0] = 1000.0f;  // black in the reference: not lit
  t.pixel(0, 0)[2] = 50.0f;    // value 1 < 4.95: not lit under the mask below
  for (int i = 0; i < 200; ++i) t.rgba[4 * i + 3] = 0.25f;
  const ErrorMask mask{0.05, 0.01, 0.99};
  EXPECT_EQ(compare_images(t, ramp(), mask).rel_rmse, 0.0);
  // Blue doubled everywhere: luminance changes by only 7 %, yet the RGB error is
  // sqrt(sum r^2 / (3 sum r^2)) = 1/sqrt(3) and the bias 1/3.
  Image blue = ramp();
  for (int i = 0; i < 200; ++i) blue.rgba[4 * i + 2] *= 2.0f;
  const auto e = compare_images(blue, ramp(), mask);
  EXPECT_NEAR(e.rel_rmse, 1.0 / std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(e.mean_bias, 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(e.max_rel, 1.0, 1e-9);
}

TEST(ImageMetrics, RefusesMismatchedSizesNonFiniteValuesBadMasksAndBlackReferences) {
  expect_error([] { compare_images(Image(20, 11), ramp()); }, "test 20x11, reference 20x10");
  Image nan = ramp();
  nan.pixel(3, 4)[1] = std::numeric_limits<float>::quiet_NaN();
  expect_error([&] { compare_images(nan, ramp()); }, "test image: pixel (3, 4) channel G is NaN");
  expect_error([&] { compare_images(ramp(), nan); }, "reference image: pixel (3, 4) channel G is NaN");
  expect_error([] { compare_images(ramp(), ramp(), {1.0, 0.01, 0.99}); }, "lit_fraction");
  expect_error([] { compare_images(ramp(), ramp(), {0.1, 0.0, 0.99}); }, "floor_fraction");
  expect_error([] { compare_images(ramp(), ramp(), {0.1, 0.01, 0.0}); }, "percentile");
  expect_error([] { compare_images(Image(4, 4), Image(4, 4)); }, "no lit pixel");
}


// A reference with 20 % Gaussian noise per value (its standard error known): against the true
// image scaled by 1.05 the plain RMSE is dominated by the reference's noise (about 0.2), while the
// corrected one recovers the 5 % (within 0.01 over 60,000 values); the true image itself scores
// about 0, and so does the reference against itself.
TEST(ImageMetrics, NoiseCorrectedErrorTakesTheReferencesVarianceOut) {
  const int w = 200, h = 100;
  Image truth(w, h), ref(w, h), scaled(w, h);
  std::vector<float> se(3 * w * h);
  std::mt19937 rng(12345);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double mu = 1.0 + 0.01 * x + 0.02 * y + 0.5 * c;
        const double s = 0.2 * mu;
        truth.pixel(x, y)[c] = static_cast<float>(mu);
        scaled.pixel(x, y)[c] = static_cast<float>(1.05 * mu);
        ref.pixel(x, y)[c] = static_cast<float>(mu + s * gauss(rng));
        se[3 * (y * w + x) + c] = static_cast<float>(s);
      }
      truth.pixel(x, y)[3] = scaled.pixel(x, y)[3] = ref.pixel(x, y)[3] = 1.0f;
    }
  EXPECT_GT(compare_images(scaled, ref).rel_rmse, 0.18);
  EXPECT_NEAR(noise_corrected_rel_rmse(scaled, ref, se), 0.05, 0.01);
  EXPECT_LT(noise_corrected_rel_rmse(truth, ref, se), 0.02);
  EXPECT_EQ(noise_corrected_rel_rmse(ref, ref, se), 0.0);
  // Without noise the correction changes nothing.
  const std::vector<float> zero(se.size(), 0.0f);
  EXPECT_NEAR(noise_corrected_rel_rmse(scaled, truth, zero), compare_images(scaled, truth).rel_rmse, 1e-9);
}

TEST(ImageMetrics, NoiseCorrectedErrorRefusesBadStandardErrors) {
  const std::vector<float> good(3 * 200, 1.0f);
  expect_error([&] { noise_corrected_rel_rmse(ramp(), ramp(), std::vector<float>(5, 0.0f)); }, "expected 3 values per pixel (600), got 5");
  std::vector<float> bad = good;
  bad[3 * 41 + 2] = -1.0f;
  expect_error([&] { noise_corrected_rel_rmse(ramp(), ramp(), bad); }, "pixel (1, 2) channel B");
  bad[3 * 41 + 2] = std::numeric_limits<float>::quiet_NaN();
  expect_error([&] { noise_corrected_rel_rmse(ramp(), ramp(), bad); }, "not finite");
  expect_error([&] { noise_corrected_rel_rmse(Image(20, 11), ramp(), good); }, "test 20x11, reference 20x10");
}

}  // namespace
