// The wavelet-noise tile (Cook & DeRose 2005): the analysis filter and the B-spline
// refinement form a projection (D U = identity, so U D is idempotent and the band-pass
// residual r - U D r has no coarse part), and the tile is deterministic in (n, seed), differs
// between seeds, and lies in [-1, 1] with 4 standard deviations mapped to 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::Rng;

double max_abs(const std::vector<float>& v) {
  double m = 0.0;
  for (float x : v) m = std::max(m, double(std::fabs(x)));
  return m;
}

// D U = I to float rounding: the filter holds every tap up to n = 64 and drops only taps below
// 3e-6 beyond.
double projection_tolerance(int) { return 1e-5; }

class NoisePropsWaveletFilter : public ::testing::TestWithParam<int> {};

double max_projection_error(int n) {
  const int m = n / 2;
  const AnalysisFilter f = wavelet_analysis_filter(n);
  Rng rng{static_cast<uint64_t>(n)};
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<float> c(m), fine(n), back(m);
    for (float& x : c) x = static_cast<float>(rng.uniform(-1.0, 1.0));
    wavelet_upsample(c.data(), fine.data(), n);
    wavelet_downsample(fine.data(), back.data(), n, f);
    for (int k = 0; k < m; ++k) worst = std::max(worst, double(std::fabs(back[k] - c[k])));
  }
  return worst;
}

TEST_P(NoisePropsWaveletFilter, DownsampleOfUpsampleIsIdentity) {
  const int n = GetParam();
  const double worst = max_projection_error(n);
  const AnalysisFilter f = wavelet_analysis_filter(n);
  std::printf("n=%d: max |D(U(c)) - c| = %.3g (taps %zu, first %d)\n", n, worst, f.taps.size(), f.first);
  RecordProperty("max_err", std::to_string(worst));
  EXPECT_LE(worst, projection_tolerance(n));
}

// The projection keeps constants: the analysis taps sum to 1 (a truncation at 24 taps per side
// once left them at 1 - 3.5e-5).
TEST(NoisePropsWaveletFilterStrict, DownsampleOfUpsampleIsIdentityTo1em5AtEverySize) {
  for (int n : {32, 64, 128}) EXPECT_LE(max_projection_error(n), 1e-5) << "n " << n;
  for (int n : {64, 128}) {
    const AnalysisFilter f = wavelet_analysis_filter(n);
    EXPECT_NEAR(std::accumulate(f.taps.begin(), f.taps.end(), 0.0), 1.0, 1e-5) << "n " << n;
  }
}

TEST_P(NoisePropsWaveletFilter, BandPassResidualHasNoCoarsePart) {
  const int n = GetParam(), m = n / 2;
  const AnalysisFilter f = wavelet_analysis_filter(n);
  Rng rng(uint64_t(n) + 1000);
  double worst = 0.0, coarse_part = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<float> r(n), half(m), rc(n), resid(n), d(m);
    for (float& x : r) x = static_cast<float>(rng.uniform(-1.0, 1.0));
    wavelet_downsample(r.data(), half.data(), n, f);
    wavelet_upsample(half.data(), rc.data(), n);
    for (int i = 0; i < n; ++i) resid[i] = r[i] - rc[i];
    wavelet_downsample(resid.data(), d.data(), n, f);
    worst = std::max(worst, max_abs(d) / max_abs(r));
    coarse_part = std::max(coarse_part, max_abs(half) / max_abs(r));
    // U D is idempotent: projecting the coarse part again changes nothing.
    std::vector<float> half2(m), rc2(n);
    wavelet_downsample(rc.data(), half2.data(), n, f);
    wavelet_upsample(half2.data(), rc2.data(), n);
    for (int i = 0; i < n; ++i)
      ASSERT_NEAR(rc2[i], rc[i], projection_tolerance(n)) << "n " << n << " i " << i;
  }
  std::printf("n=%d: max |D(r - U D r)| / max|r| = %.3g (D r itself: %.3g)\n", n, worst, coarse_part);
  EXPECT_LE(worst, 1e-4);
  EXPECT_GT(coarse_part, 0.1);  // the check is not vacuous: D r is not small
}

TEST_P(NoisePropsWaveletFilter, FilterIsSymmetricAndPreservesConstants) {
  const int n = GetParam();
  const AnalysisFilter f = wavelet_analysis_filter(n);
  ASSERT_FALSE(f.taps.empty());
  // Symmetric about -1/2: tap at offset o equals the tap at offset -1 - o.
  const int size = int(f.taps.size());
  for (int i = 0; i < size; ++i) {
    const int o = f.first + i, mirror = -1 - o - f.first;
    if (mirror >= 0 && mirror < size) {
      EXPECT_NEAR(f.taps[i], f.taps[mirror], 1e-7) << "offset " << o;
    }
  }
  // Constants are in the coarse space: D(1) = 1, so the taps sum to 1.
  const double sum = std::accumulate(f.taps.begin(), f.taps.end(), 0.0);
  EXPECT_NEAR(sum, 1.0, projection_tolerance(n));
  // The central taps are Cook & DeRose's 0.655340 (their appendix table).
  EXPECT_NEAR(f.taps[size_t(-f.first)], 0.655340, 2e-6);
  EXPECT_NEAR(f.taps[size_t(-f.first - 1)], 0.655340, 2e-6);
}

INSTANTIATE_TEST_SUITE_P(Sizes, NoisePropsWaveletFilter, ::testing::Values(32, 64, 128));

TEST(NoisePropsWaveletTile, DeterministicPerSeedAndDifferentAcrossSeeds) {
  const int n = 32;
  const size_t count = size_t(n) * n * n;
  const WaveletTile a(n, 7), b(n, 7), c(n, 8);
  EXPECT_EQ(a.size(), n);
  EXPECT_EQ(a.seed(), 7u);
  EXPECT_TRUE(std::equal(a.data(), a.data() + count, b.data(),
                         [](float x, float y) { return test::bits(x) == test::bits(y); }));
  size_t same = 0;
  for (size_t i = 0; i < count; ++i) same += a.data()[i] == c.data()[i];
  EXPECT_LT(same, count / 100);
  // The tile of a size is not a crop of another size's.
  const WaveletTile d(34, 7);
  same = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) same += a.at(x, y, z) == d.at(x, y, z);
  EXPECT_LT(same, count / 100);
}

TEST(NoisePropsWaveletTile, CoefficientsInRangeAndNormalised) {
  for (int n : {8, 32, 64, 128}) {
    for (uint32_t seed : {0u, 1u, 99u}) {
      const WaveletTile t(n, seed);
      const size_t count = size_t(n) * n * n;
      double sum = 0.0, sum2 = 0.0;
      float lo = 1.0f, hi = -1.0f;
      for (size_t i = 0; i < count; ++i) {
        const float v = t.data()[i];
        ASSERT_TRUE(std::isfinite(v));
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        sum += v;
        sum2 += double(v) * v;
      }
      const double mean = sum / double(count), rms = std::sqrt(sum2 / double(count));
      if (n >= 32 && seed == 0)
        std::printf("tile n=%d: [%.4f, %.4f] mean %+.2e rms %.5f clamped %lld band_sd %.4f\n", n,
                    double(lo), double(hi), mean, rms, static_cast<long long>(t.clamped()), t.band_sd());
      EXPECT_GE(lo, -1.0f);
      EXPECT_LE(hi, 1.0f);
      // The band-pass residual has zero mean exactly (constants are coarse), so up to rounding.
      EXPECT_LE(std::fabs(mean), 1e-5) << "n " << n;
      // "4 standard deviations map to 1": RMS 0.25 when nothing was clamped.
      EXPECT_EQ(t.clamped(), 0);
      EXPECT_NEAR(rms, 1.0 / kWaveletClampSigmas, 1e-5) << "n " << n;
      EXPECT_NEAR(t.scale(), 1.0 / (kWaveletClampSigmas * t.band_sd()), 1e-12);
    }
  }
}

TEST(NoisePropsWaveletTile, SharedTilesAreReusedWhileAlive) {
  auto a = WaveletTile::shared(16, 4);
  auto b = WaveletTile::shared(16, 4);
  auto c = WaveletTile::shared(16, 5);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_NE(a.get(), c.get());
  NoiseParams p;
  p.kind = Kind::Wavelet;
  p.tile_size = 16;
  p.seed = 4;
  const NoiseField f(p);
  EXPECT_EQ(f.tile(), a.get());
}

TEST(NoisePropsWaveletTile, BadSizesThrow) {
  EXPECT_THROW(WaveletTile(7, 0), std::invalid_argument);
  EXPECT_THROW(WaveletTile(6, 0), std::invalid_argument);
  EXPECT_THROW(WaveletTile(514, 0), std::invalid_argument);
  EXPECT_THROW(WaveletTile(33, 0), std::invalid_argument);
  EXPECT_THROW(wavelet_analysis_filter(6), std::invalid_argument);
  EXPECT_THROW(wavelet_analysis_filter(31), std::invalid_argument);
}

// Wavelet noise of the tile through the kernel equals the quadratic B-spline sum of the tile's
// coefficients (independent evaluation): with frequency 1, no animation, the coefficient
// offsets are a fixed integer shift, found here by matching.
TEST(NoisePropsWaveletTile, NoiseIsTheBSplineSumOfTheTile) {
  NoiseParams p;
  p.kind = Kind::Wavelet;
  p.tile_size = 16;
  p.seed = 12;
  const NoiseField f(p);
  const WaveletTile& t = *f.tile();
  const int n = t.size();
  auto bspline = [](double x) {
    x = std::fabs(x);
    return x < 0.5 ? 0.75 - x * x : (x < 1.5 ? 0.5 * (1.5 - x) * (1.5 - x) : 0.0);
  };
  auto direct = [&](double x, double y, double z, int ox, int oy, int oz) {
    double s = 0.0;
    const int cx = int(std::floor(x + 0.5)), cy = int(std::floor(y + 0.5)), cz = int(std::floor(z + 0.5));
    for (int k = cz - 1; k <= cz + 1; ++k)
      for (int j = cy - 1; j <= cy + 1; ++j)
        for (int i = cx - 1; i <= cx + 1; ++i)
          s += bspline(x - i) * bspline(y - j) * bspline(z - k) *
               t.at(((i + ox) % n + n) % n, ((j + oy) % n + n) % n, ((k + oz) % n + n) % n);
    return s;
  };
  // At lattice nodes the noise is (1/8, 3/4, 1/8)^3-weighted; find the offset from a few nodes.
  int off[3] = {-1, -1, -1};
  for (int ox = 0; ox < n && off[0] < 0; ++ox)
    for (int oy = 0; oy < n && off[0] < 0; ++oy)
      for (int oz = 0; oz < n && off[0] < 0; ++oz) {
        bool ok = true;
        for (int q = 0; q < 4 && ok; ++q)
          ok = std::fabs(direct(q, 2 * q, 3 * q, ox, oy, oz) - f.eval(q, 2 * q, 3 * q)) < 1e-6;
        if (ok) off[0] = ox, off[1] = oy, off[2] = oz;
      }
  ASSERT_GE(off[0], 0) << "no integer tile offset reproduces the noise at lattice nodes";
  Rng rng(4);
  double worst = 0.0;
  for (int i = 0; i < 5000; ++i) {
    const double x = rng.uniform(-40, 40), y = rng.uniform(-40, 40), z = rng.uniform(-40, 40);
    worst = std::max(worst, std::fabs(direct(x, y, z, off[0], off[1], off[2]) - f.eval(x, y, z)));
  }
  EXPECT_LE(worst, 1e-6);
}

}  // namespace
}  // namespace nimbus::noise
