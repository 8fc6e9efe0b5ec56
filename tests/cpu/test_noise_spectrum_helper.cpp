// The spectrum helper itself (support/spectrum.hpp), on signals whose spectrum is known: plane
// waves put their energy at |f| and on the cone around their direction, white noise is flat
// and therefore isotropic, Parseval holds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "support/spectrum.hpp"

namespace nimbus::test {
namespace {

// cos(2 pi f . x + phase) on a dims grid, x fastest, f given as integer bin indices k: at any
// spacing, f_a = k_a / (n_a spacing) lies exactly on the FFT grid.
std::vector<float> plane_wave(std::array<int, 3> dims, std::array<int, 3> k,
                              double amplitude = 1.0, double phase = 0.3) {
  std::vector<float> v(static_cast<size_t>(dims[0]) * dims[1] * dims[2]);
  size_t i = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        const double arg = double(k[0]) * x / dims[0] + double(k[1]) * y / dims[1] +
                           double(k[2]) * z / dims[2];
        v[i++] = static_cast<float>(amplitude * std::cos(2.0 * std::numbers::pi * arg + phase));
      }
  return v;
}

std::array<double, 3> freq(std::array<int, 3> dims, double spacing, std::array<int, 3> k) {
  return {k[0] / (dims[0] * spacing), k[1] / (dims[1] * spacing), k[2] / (dims[2] * spacing)};
}

double norm(std::array<double, 3> f) { return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); }

TEST(SpectrumHelper, PlaneWaveWithoutWindowSitsExactlyAtItsFrequency) {
  // Non-cubic dims and a frequency with all three components different catch any mix-up of
  // the axis order between the sample layout (x fastest) and kissfft (last dim fastest).
  const std::array<int, 3> dims{64, 48, 40};
  const double spacing = 0.5;
  const std::array<int, 3> k{5, -7, 9};
  const auto f = freq(dims, spacing, k);
  const double r = norm(f);
  const PowerSpectrum s(plane_wave(dims, k), dims, spacing, Window::None);

  EXPECT_NEAR(s.total(), 0.5, 1e-4);  // Parseval: mean of cos^2
  EXPECT_NEAR(s.share({r - 1e-4, r + 1e-4}), 1.0, 1e-5);
  EXPECT_EQ(s.df(0), 1.0 / 32);
  EXPECT_EQ(s.nyquist(), 1.0);

  // All of it on the 1-degree cone around f and around -f (the mirror), none elsewhere.
  const std::array<double, 3> dirs[] = {f, {-f[0], -f[1], -f[2]}, {f[0], -f[1], f[2]}};
  const Band all{0.0, 10.0};
  EXPECT_NEAR(s.cones(std::span(dirs, 1), 1.0, all).power, 0.25, 1e-4);
  EXPECT_NEAR(s.cones(std::span(dirs + 1, 1), 1.0, all).power, 0.25, 1e-4);
  EXPECT_NEAR(s.cones(std::span(dirs + 2, 1), 10.0, all).power, 0.0, 1e-6);
  EXPECT_EQ(s.cones(std::span(dirs, 1), 1.0, {r - 1e-4, r + 1e-4}).count, 1.0);

  const Band oct = s.best_octave();
  EXPECT_LE(oct.lo, r);
  EXPECT_GT(oct.hi, r);
}

TEST(SpectrumHelper, PlaneWaveWithHannWindowStaysOnItsConeAndRadius) {
  const std::array<int, 3> dims{64, 64, 64};
  const double spacing = 0.25;
  const std::array<int, 3> k{12, 20, -8};  // |k| = 24.7 bins: the window's +-1 bin spread is < 4 deg
  const auto f = freq(dims, spacing, k);
  const double r = norm(f), df = 1.0 / (64 * spacing);
  const PowerSpectrum s(plane_wave(dims, k, 2.0), dims, spacing, Window::Hann);

  // Hann: mean of w^2 is (3/8)^3 per 3D sample, times the wave's mean square 2.
  EXPECT_NEAR(s.total(), 2.0 * std::pow(3.0 / 8.0, 3), 1e-4);
  // The periodic Hann window spreads an on-grid frequency over bins k-1..k+1 only.
  EXPECT_GT(s.share({r - 1.8 * df, r + 1.8 * df}), 0.999999);
  const std::array<double, 3> both[] = {f, {-f[0], -f[1], -f[2]}};
  EXPECT_GT(s.cones(both, 5.0, {0.0, 10.0}).power / s.total(), 0.999999);
  const Band oct = s.best_octave();
  EXPECT_LE(oct.lo, r);
  EXPECT_GT(oct.hi, r);
}

TEST(SpectrumHelper, PlaneWave2D) {
  const std::array<int, 3> dims{64, 32, 1};
  const double spacing = 0.25;
  const std::array<int, 3> k{3, 11, 0};
  const auto f = freq({64, 32, 1}, spacing, k);
  const double r = std::hypot(f[0], f[1]);
  const PowerSpectrum s(plane_wave(dims, k), dims, spacing, Window::None);
  EXPECT_NEAR(s.total(), 0.5, 1e-4);
  EXPECT_NEAR(s.share({r - 1e-4, r + 1e-4}), 1.0, 1e-5);
  const std::array<double, 3> dir[] = {{f[0], f[1], 0.0}};
  EXPECT_NEAR(s.cones(dir, 1.0, {0.0, 10.0}).power, 0.25, 1e-4);

  // Two slices accumulate.
  PowerSpectrum sum = s;
  sum.accumulate(PowerSpectrum(plane_wave(dims, {5, 0, 0}), dims, spacing, Window::None));
  EXPECT_NEAR(sum.total(), 1.0, 2e-4);
  EXPECT_NEAR(sum.energy({r - 1e-4, r + 1e-4}), 0.5, 1e-4);
  EXPECT_NEAR(sum.energy({5.0 / 16 - 1e-4, 5.0 / 16 + 1e-4}), 0.5, 1e-4);
}

TEST(SpectrumHelper, RadialHistogramAndBestOctave) {
  // A strong wave at |f| = 10 bins and a weak one at 40 bins: the best octave holds the strong
  // one, the histogram puts each where it belongs and sums to the total.
  const std::array<int, 3> dims{128, 8, 2};
  const double spacing = 1.0 / 128;  // df = 1 along x
  std::vector<float> a = plane_wave(dims, {10, 0, 0}, 1.0);
  const std::vector<float> b = plane_wave(dims, {40, 0, 0}, 0.5);
  for (size_t i = 0; i < a.size(); ++i) a[i] += b[i];
  const PowerSpectrum s(a, dims, spacing, Window::None);
  const auto h = s.radial_histogram(1.0);
  double sum = 0.0;
  for (double e : h) sum += e;
  EXPECT_NEAR(sum, s.total(), 1e-9);
  EXPECT_NEAR(h[10], 0.5, 1e-4);
  EXPECT_NEAR(h[40], 0.125, 1e-4);
  const Band oct = s.best_octave();
  EXPECT_LE(oct.lo, 10.0);
  EXPECT_GT(oct.hi, 10.0);
  EXPECT_NEAR(s.share(oct), 0.8, 1e-4);
  EXPECT_NEAR(s.share_below(20.0), 0.8, 1e-4);
  EXPECT_NEAR(s.share_at_or_above(40.0), 0.2, 1e-4);
}

TEST(SpectrumHelper, WhiteNoiseIsIsotropic) {
  // Flat spectrum: equal power density on the axis and diagonal cones. 128^3 so that the
  // cones hold ~50 000 bins each (statistical error about 1 %).
  const std::array<int, 3> dims{128, 128, 128};
  std::vector<float> v(size_t(128) * 128 * 128);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (float& x : v) x = u(rng);
  for (Window w : {Window::None, Window::Hann}) {
    const PowerSpectrum s(v, dims, 0.25, w);
    const Band band{s.nyquist() / 8, s.nyquist()};
    const double ratio = isotropy_ratio(s, band);
    std::printf("[spectrum] white noise isotropy ratio (%s window): %.4f\n",
                w == Window::Hann ? "Hann" : "no", ratio);
    EXPECT_NEAR(ratio, 1.0, 0.05);
    // Sanity of the density: axis and diagonal cones of 10 degrees each hold about
    // 2 pi (1 - cos 10 deg) / (4 pi) = 0.76 % of the shell's bins.
    const ConeStats axes = s.cones(axis_directions(), 10.0, band);
    const double shell = 4.0 / 3.0 * std::numbers::pi * (std::pow(64.0, 3) - std::pow(8.0, 3));
    EXPECT_NEAR(axes.count / (6 * shell), 0.5 * (1 - std::cos(10.0 * std::numbers::pi / 180)), 0.001);
  }
}

TEST(SpectrumHelper, AxisAlignedWavesAreAnisotropic) {
  const std::array<int, 3> dims{64, 64, 64};
  // Three axis-aligned waves over faint white noise (so that the diagonal cones hold some).
  std::vector<float> v(size_t(64) * 64 * 64);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.01f, 0.01f);
  for (float& x : v) x = u(rng);
  for (const auto& k : {std::array<int, 3>{16, 0, 0}, {0, 16, 0}, {0, 0, 16}}) {
    const auto w = plane_wave(dims, k);
    for (size_t i = 0; i < v.size(); ++i) v[i] += w[i];
  }
  const PowerSpectrum s(v, dims, 0.25);
  const double ratio = isotropy_ratio(s, {0.5, 2.0});
  EXPECT_TRUE(std::isfinite(ratio));
  EXPECT_GT(ratio, 100.0);
}

}  // namespace
}  // namespace nimbus::test
