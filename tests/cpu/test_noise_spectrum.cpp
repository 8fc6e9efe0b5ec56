// Spectral tests of the noise kinds (the protocol of the independent figures in docs/noise.md):
// 128^3 samples at spacing 0.25 lattice units (frequency 1), mean removed, 3D Hann window,
// power binned by radial frequency |f| in cycles per lattice unit. The "best octave" is the
// band [lo, 2 lo) holding the most energy (every lo where the band energy can change is tried).
// Every measured number is printed with a "[spectrum]" prefix so it can be copied into docs.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "support/spectrum.hpp"

namespace nimbus::test {
namespace {

using noise::Fractal;
using noise::Kind;
using noise::NoiseParams;

// Off the lattice (gradient noise is 0 at lattice points; a grid through them would see it).
constexpr std::array<double, 3> kOrigin{0.137, 0.571, 0.913};
constexpr int kN = 128;
constexpr uint32_t kSeed = 1;

const char* name(Kind k) {
  switch (k) {
    case Kind::Value: return "value";
    case Kind::Gradient: return "gradient";
    case Kind::Wavelet: return "wavelet";
    case Kind::Worley: return "worley";
  }
  return "?";
}

NoiseParams single(Kind kind) {
  NoiseParams p;
  p.kind = kind;
  p.seed = kSeed;
  return p;
}

std::vector<float> sample(const NoiseParams& p, std::array<int64_t, 3> res, double spacing,
                          std::array<double, 3> origin = kOrigin) {
  const noise::NoiseField field(p);
  noise::GridSpec g;
  g.origin = origin;
  g.spacing = spacing;
  g.res = res;
  std::vector<float> out(static_cast<size_t>(g.count()));
  noise::evaluate_grid(field, g, out);
  return out;
}

// 3D spectrum of one octave of `kind` on the 128^3 grid, computed once per (kind, spacing)
// and shared by the tests below (each costs a 128^3 FFT).
const PowerSpectrum& spectrum3d(Kind kind, double spacing) {
  static std::map<std::pair<int, double>, std::unique_ptr<PowerSpectrum>> cache;
  auto& slot = cache[{static_cast<int>(kind), spacing}];
  if (!slot)
    slot = std::make_unique<PowerSpectrum>(sample(single(kind), {kN, kN, kN}, spacing),
                                           std::array<int, 3>{kN, kN, kN}, spacing);
  return *slot;
}

double pct(double share) { return 100.0 * share; }

// 1. Wavelet noise is band-limited: most energy in one octave, little below it, almost none
// below its nominal band [0.25, 0.5).
TEST(NoiseSpectrum, WaveletSingleBandHoldsItsEnergyInOneOctave) {
  const PowerSpectrum& s = spectrum3d(Kind::Wavelet, 0.25);
  const Band oct = s.best_octave();
  const double in = s.share(oct), below = s.share_below(oct.lo);
  const double above = s.share_at_or_above(oct.hi);
  std::printf("[spectrum] wavelet 3D: best octave [%.4f, %.4f) %.1f %%, below %.1f %%, above %.1f %%\n",
              oct.lo, oct.hi, pct(in), pct(below), pct(above));
  std::printf("[spectrum] wavelet 3D: nominal band [0.25, 0.5) %.1f %%, below 0.25 %.2f %%, "
              "at or above 0.5 %.1f %%\n",
              pct(s.share({0.25, 0.5})), pct(s.share_below(0.25)), pct(s.share_at_or_above(0.5)));
  EXPECT_GE(in, 0.80);
  EXPECT_LE(below, 0.12);
  EXPECT_LE(s.share_below(0.25), 0.02);  // goal: under 2 % below the band
}

// 2. Gradient noise: a regression floor on its best-octave share. Value noise: reported only.
TEST(NoiseSpectrum, GradientAndValueOctaveShares) {
  for (Kind kind : {Kind::Gradient, Kind::Value}) {
    const PowerSpectrum& s = spectrum3d(kind, 0.25);
    const Band oct = s.best_octave();
    std::printf("[spectrum] %s 3D: best octave [%.4f, %.4f) %.1f %%, below %.1f %%, above %.1f %%\n",
                name(kind), oct.lo, oct.hi, pct(s.share(oct)), pct(s.share_below(oct.lo)),
                pct(s.share_at_or_above(oct.hi)));
    if (kind == Kind::Gradient) {
      EXPECT_GE(s.share(oct), 0.70);
    }
  }
}

// 3. Cook & DeRose's point: a 2D slice of band-limited 3D noise is not band-limited (the
// slice integrates the 3D spectrum over the frequencies normal to it, including the low |f|
// in the slice plane), while the projected evaluation keeps slices band-limited.
//
// "Below the band" here means below 0.25 cycles per lattice unit, the bottom of wavelet
// noise's nominal band [0.25, 0.5) (half the coefficient grid's Nyquist). It is a fixed
// number, the same for both variants and independent of any measured octave, and it is the
// definition under which an independent run of Cook & DeRose's appendix code measured 23.4 %
// for plain slices. The share below the 3D best octave's lo (about 0.29-0.31) is printed too,
// since that run quotes the slice leakage under that definition as well.
//
// Goal: projected slices keep <= 5 % below the band (nimbus's own bar: Cook & DeRose state no
// figure).
// With Cook & DeRose's halfway move (a B-spline stretched by k = 2 along the normal) nimbus
// measured 5.6 % (5.3-6.0 % over seeds, depths and sizes): the sinc^3(2 f_n) response still
// passes 6.6 % of the power at f_n = 1/4. nimbus stretches by kProjectionStretch = 3
// (sinc^3(3 f_n): 0.07 %), which measures 3.2 %.
TEST(NoiseSpectrum, ProjectedWaveletSlicesStayBandLimited) {
  constexpr int kSlice = 256, kSlices = 4;
  constexpr double kSpacing = 0.25;
  constexpr double kBandBottom = 0.25;
  constexpr double kGoal = 0.05;
  const double octave_lo = spectrum3d(Kind::Wavelet, 0.25).best_octave().lo;

  double below_band[2], below_lo[2];
  for (int projected = 0; projected < 2; ++projected) {
    NoiseParams p = single(Kind::Wavelet);
    p.projected = projected != 0;
    p.normal = {0.0, 0.0, 1.0};
    std::unique_ptr<PowerSpectrum> sum;
    for (int k = 0; k < kSlices; ++k) {
      // Slices 7.3 lattice units apart: independent, at different offsets to the coefficient
      // planes.
      const std::array<double, 3> origin{kOrigin[0], kOrigin[1], kOrigin[2] + 7.3 * k};
      const auto v = sample(p, {kSlice, kSlice, 1}, kSpacing, origin);
      PowerSpectrum s(v, {kSlice, kSlice, 1}, kSpacing);
      if (sum) {
        sum->accumulate(s);
      } else {
        sum = std::make_unique<PowerSpectrum>(std::move(s));
      }
    }
    const Band oct = sum->best_octave();
    below_band[projected] = sum->share_below(kBandBottom);
    below_lo[projected] = sum->share_below(octave_lo);
    std::printf("[spectrum] wavelet %s, %d z-slices %d^2: below %.2f: %.1f %%, below 3D octave lo "
                "%.4f: %.1f %%; 2D best octave [%.4f, %.4f) %.1f %%\n",
                projected ? "projected" : "plain    ", kSlices, kSlice, kBandBottom,
                pct(below_band[projected]), octave_lo, pct(below_lo[projected]), oct.lo, oct.hi,
                pct(sum->share(oct)));
  }
  std::printf("[spectrum] projected-slice goal <= %.0f %% below %.2f: %s\n", pct(kGoal), kBandBottom,
              below_band[1] <= kGoal ? "met" : "NOT MET");
  EXPECT_LE(below_band[1], kGoal);
  EXPECT_GT(below_band[0], below_band[1] + 0.10);
}

// 4. fBm: octave i of a lacunarity-2 sum has amplitude gain^i, so the energy in the octave
// bands [lo 2^i, lo 2^(i+1)) falls by about gain^2 per band, lo being the single band's best
// octave. Finer spacing (Nyquist 6.25) so that the 4th band [8 lo, 16 lo) ~ [2.5, 5) is
// resolved; 160^3 keeps the lowest band several frequency bins wide.
TEST(NoiseSpectrum, WaveletFbmOctaveEnergiesFallByGainSquared) {
  constexpr int kM = 160;
  constexpr double kSpacing = 0.08;
  NoiseParams p = single(Kind::Wavelet);
  p.fractal = Fractal::Fbm;
  p.octaves = 4;
  p.lacunarity = 2.0;
  p.gain = 0.5;
  const double g2 = p.gain * p.gain;
  const PowerSpectrum s(sample(p, {kM, kM, kM}, kSpacing), {kM, kM, kM}, kSpacing);
  const double lo = spectrum3d(Kind::Wavelet, 0.25).best_octave().lo;
  ASSERT_LT(16 * lo, s.nyquist());
  double e[4];
  for (int i = 0; i < 4; ++i) e[i] = s.share({lo * (1 << i), lo * (2 << i)});
  std::printf("[spectrum] wavelet fBm 4 oct (gain %.2f): band shares %.1f %%, %.1f %%, %.1f %%, "
              "%.2f %%; ratios %.3f, %.3f, %.3f (gain^2 = %.3f)\n",
              p.gain, pct(e[0]), pct(e[1]), pct(e[2]), pct(e[3]), e[1] / e[0], e[2] / e[1],
              e[3] / e[2], g2);
  for (int i = 1; i < 4; ++i) {
    const double ratio = e[i] / e[i - 1];
    EXPECT_GE(ratio, 0.5 * g2) << "band " << i;
    EXPECT_LE(ratio, 2.0 * g2) << "band " << i;
  }
}

// 5. Isotropy: power density on 10-degree cones around the 6 axis directions over that around
// the 8 body diagonals, within the best octave (measured independently: Perlin's 2002 reference
// 1.31-1.33, Cook & DeRose's separable wavelet 1.37, FastNoiseLite's value noise 0.83 and
// OpenSimplex2 1.06).
//
// One 128^3 realisation is too few bins for this: a 10-degree cone holds only ~180 (wavelet) to
// ~900 (gradient) frequency samples in the octave, and single seeds scatter by +-10 % (gradient)
// to +-30 % (wavelet). So the spectra of kIsoSeeds seeds are summed first; the single-seed
// ratios are printed as well. Cross-check: the lattice-averaged spectra of the kernels
// (value: prod |W(f_a)|^2, gradient: sum_a |W1(f_a)|^2 prod_(b != a) |W(f_b)|^2, with W and
// W1 the transforms of the quintic-fade weight w(t) and of t w(t)) give 0.92 (value) and 1.25
// (gradient) on these cones and octaves.
//
// No nimbus mode is documented as isotropic today, so only gradient noise's known anisotropy
// is asserted. ANY MODE THAT IS DOCUMENTED AS ISOTROPIC MUST BE ADDED HERE WITH A RATIO
// <= 1.10 (FastNoiseLite's OpenSimplex2 measures 1.06).
TEST(NoiseSpectrum, IsotropyRatios) {
  constexpr int kIsoSeeds = 6;
  for (Kind kind : {Kind::Value, Kind::Gradient, Kind::Wavelet}) {
    PowerSpectrum sum = spectrum3d(kind, 0.25);  // seed kSeed
    std::vector<double> single_ratios{isotropy_ratio(sum, sum.best_octave())};
    for (uint32_t seed = kSeed + 1; seed < kSeed + kIsoSeeds; ++seed) {
      NoiseParams p = single(kind);
      p.seed = seed;
      const PowerSpectrum s(sample(p, {kN, kN, kN}, 0.25), {kN, kN, kN}, 0.25);
      single_ratios.push_back(isotropy_ratio(s, s.best_octave()));
      sum.accumulate(s);
    }
    const Band oct = sum.best_octave();
    const double ratio = isotropy_ratio(sum, oct, 10.0);
    std::printf("[spectrum] isotropy %s: axis/diagonal power ratio %.3f in [%.4f, %.4f) over %d "
                "seeds; single seeds:",
                name(kind), ratio, oct.lo, oct.hi, kIsoSeeds);
    for (double r : single_ratios) std::printf(" %.3f", r);
    std::printf("\n");
    EXPECT_TRUE(std::isfinite(ratio)) << name(kind);
    EXPECT_GT(ratio, 0.0) << name(kind);
    if (kind == Kind::Gradient) {
      EXPECT_GT(ratio, 1.1);
    }
  }
}

// 6. Band-limited ahead of aliasing: at spacing 0.125 (Nyquist 4 cycles per lattice unit)
// almost nothing lies at or above twice the best octave's top (measured independently: 0.017 %
// for Perlin's 2002 reference, 0.057 % for Cook & DeRose's appendix code).
TEST(NoiseSpectrum, NoEnergyFarAboveTheOctave) {
  for (Kind kind : {Kind::Wavelet, Kind::Gradient}) {
    const PowerSpectrum& s = spectrum3d(kind, 0.125);
    const Band oct = s.best_octave();
    const double far = s.share_at_or_above(2.0 * oct.hi);
    std::printf("[spectrum] %s 3D at spacing 0.125: best octave [%.4f, %.4f) %.1f %%, "
                "at or above %.3f: %.4f %%\n",
                name(kind), oct.lo, oct.hi, pct(s.share(oct)), 2.0 * oct.hi, pct(far));
    ASSERT_LE(2.0 * oct.hi, s.nyquist());
    EXPECT_LE(far, 0.005) << name(kind);
  }
}

}  // namespace
}  // namespace nimbus::test
