// Blue-noise tiles (void-and-cluster): an exact rank permutation, a spectrum without low
// frequencies, neighbours that differ more than white noise's, every threshold level spread
// out, and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "nimbus/render/core/blue_noise.hpp"
#include "support/spectrum.hpp"

namespace {

using nimbus::render::blue_noise_ranks;
using nimbus::render::blue_noise_tile;

std::vector<float> white_tile(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<float> t(static_cast<std::size_t>(n) * n);
  for (float& v : t) v = static_cast<float>((rng() + 0.5) / 4294967296.0);
  return t;
}

// Share of the tile's (mean-removed, unwindowed: the tile is periodic) power at |f| < f_max
// cycles per pixel.
double low_share(const std::vector<float>& tile, int n, double f_max) {
  const nimbus::test::PowerSpectrum s(tile, {n, n, 1}, 1.0, nimbus::test::Window::None);
  return s.share_below(f_max);
}

// Mean |difference| of horizontally and vertically adjacent values on the torus.
double neighbour_difference(const std::vector<float>& t, int n) {
  double sum = 0.0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const double v = t[y * n + x];
      sum += std::abs(v - t[y * n + (x + 1) % n]) + std::abs(v - t[((y + 1) % n) * n + x]);
    }
  }
  return sum / (2.0 * n * n);
}

// Smallest toroidal distance (pixels) between two pixels whose value is below `level`.
double min_distance_below(const std::vector<float>& t, int n, double level) {
  std::vector<std::pair<int, int>> pts;
  for (int i = 0; i < n * n; ++i) {
    if (t[i] < level) pts.emplace_back(i % n, i / n);
  }
  double best = n;
  for (std::size_t a = 0; a < pts.size(); ++a) {
    for (std::size_t b = a + 1; b < pts.size(); ++b) {
      const int dx = std::abs(pts[a].first - pts[b].first), dy = std::abs(pts[a].second - pts[b].second);
      const int tx = std::min(dx, n - dx), ty = std::min(dy, n - dy);
      best = std::min(best, std::sqrt(double(tx * tx + ty * ty)));
    }
  }
  return best;
}

TEST(BlueNoise, RanksAreAPermutationAndValuesAreUniform) {
  for (const int n : {16, 64, 256}) {
    const std::vector<std::uint32_t> rank = blue_noise_ranks(n, 7);
    std::vector<std::uint32_t> sorted = rank;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i) << "size " << n;
  }
  // (i + 0.5) / N is exact in float for N <= 2^16, so the histogram is exactly one per level.
  const std::vector<float> tile = blue_noise_tile(64, 7);
  std::vector<float> sorted = tile;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], (i + 0.5f) / 4096.0f);
}

TEST(BlueNoise, SizeMustBeAPowerOfTwoFrom16To256) {
  for (const int n : {0, -16, 8, 48, 100, 512}) {
    try {
      blue_noise_tile(n, 1);
      ADD_FAILURE() << "size " << n << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("size"), std::string::npos) << e.what();
    }
  }
}

TEST(BlueNoise, DeterministicForASeed) {
  EXPECT_EQ(blue_noise_ranks(32, 123), blue_noise_ranks(32, 123));
  const auto a = blue_noise_ranks(32, 123), b = blue_noise_ranks(32, 124);
  int same = 0;
  for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == b[i];
  EXPECT_LT(same, 64) << "seeds 123 and 124 give nearly the same map";  // 1 in 1024 by chance
}

TEST(BlueNoise, SpectrumHasLittleLowFrequencyEnergy) {
  const int n = 64;
  const double f = 0.125;  // cycles per pixel: a quarter of Nyquist, periods longer than 8 pixels
  double white = 0.0;
  for (std::uint32_t s = 1; s <= 8; ++s) white += low_share(white_tile(n, s), n, f) / 8.0;
  // White noise: a flat spectrum, so the share is the share of frequency samples below f,
  // pi f^2 = 4.9 %. Void-and-cluster removes the low frequencies (the blotches that show as
  // visible patterns) almost entirely: measured 1e-5 to 2e-5, i.e. 3e-4 to 4e-4 of white
  // noise's. The threshold, 1 % of white noise's share, leaves a margin of 25.
  EXPECT_NEAR(white, std::numbers::pi * f * f, 0.005);
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const double blue = low_share(blue_noise_tile(n, seed), n, f);
    EXPECT_LT(blue, 0.01 * white) << "seed " << seed;
  }
}

TEST(BlueNoise, NeighboursDifferMoreThanWhiteNoise) {
  const int n = 64;
  // For independent uniform values E|u - v| = 1/3; blue noise measured 0.408 and 0.409.
  for (std::uint32_t seed : {1u, 2u}) {
    const double blue = neighbour_difference(blue_noise_tile(n, seed), n);
    const double white = neighbour_difference(white_tile(n, seed), n);
    EXPECT_NEAR(white, 1.0 / 3.0, 0.015) << "seed " << seed;
    EXPECT_GT(blue, 1.0 / 3.0 + 0.05) << "seed " << seed;
  }
}

TEST(BlueNoise, EveryThresholdLevelIsSpreadOut) {
  const int n = 64;
  // The pixels below a threshold level form an even point set (what makes the jitter of any
  // one step count look even): at density d the mean spacing is 1 / sqrt(d) pixels. Over 40
  // seeds the smallest distance was >= 0.637 of that at d = 1/64 and 1/16 and sqrt 2 at 1/8;
  // white noise has adjacent pixels (distance 1) at all three levels.
  const auto blue = blue_noise_tile(n, 5);
  for (const double level : {1.0 / 64, 1.0 / 16}) {
    EXPECT_GE(min_distance_below(blue, n, level), 0.6 / std::sqrt(level)) << "level " << level;
  }
  EXPECT_GT(min_distance_below(blue, n, 1.0 / 8), 1.0) << "adjacent pixels at level 1/8";
}

}  // namespace
