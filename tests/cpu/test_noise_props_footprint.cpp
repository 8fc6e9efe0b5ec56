// Octave selection from the sampling footprint: an octave is kept exactly when its band top
// (frequency * lacunarity^i * band_top(kind), cycles per input unit) is at most the Nyquist
// frequency 1 / (2 spacing) of the samples; the first octave is always kept and flagged when
// it aliases; the requested count is an upper bound; bad spacings throw.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "nimbus/noise/noise.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::Rng;

NoiseParams fbm(Kind kind, int octaves, double frequency, double lacunarity) {
  NoiseParams p;
  p.kind = kind;
  p.fractal = Fractal::Fbm;
  p.octaves = octaves;
  p.frequency = frequency;
  p.lacunarity = lacunarity;
  return p;
}

TEST(NoisePropsFootprint, BandTopsFollowTheMeasuredSpectra) {
  // Measured independently (Perlin's 2002 reference, FastNoiseLite's value noise): gradient
  // noise's best octave is [0.5, 1), value noise's [0.34, 0.69); wavelet noise's nominal band is
  // [0.25, 0.5) (cycles per lattice unit).
  EXPECT_DOUBLE_EQ(band_top(Kind::Gradient), 1.0);
  EXPECT_DOUBLE_EQ(band_top(Kind::Wavelet), 0.5);
  EXPECT_GE(band_top(Kind::Value), 0.69);
  EXPECT_LE(band_top(Kind::Value), 0.70);
}

TEST(NoisePropsFootprint, ExactBoundaryCases) {
  // Gradient, frequency 1, lacunarity 2: band tops 1, 2, 4, 8, ... With spacing 1/8 the
  // Nyquist limit is 4: octaves with tops 1, 2, 4 fit (4 == 4 is kept), 8 does not.
  OctaveChoice c = octaves_for_footprint(fbm(Kind::Gradient, 8, 1.0, 2.0), 0.125);
  EXPECT_EQ(c.octaves, 3);
  EXPECT_EQ(c.requested, 8);
  EXPECT_DOUBLE_EQ(c.nyquist, 4.0);
  EXPECT_DOUBLE_EQ(c.top_frequency, 4.0);
  EXPECT_FALSE(c.first_aliased);
  // Just finer spacing: the fourth octave still does not fit; just coarser: the third drops.
  EXPECT_EQ(octaves_for_footprint(fbm(Kind::Gradient, 8, 1.0, 2.0), 0.125 * (1 - 1e-12)).octaves, 3);
  EXPECT_EQ(octaves_for_footprint(fbm(Kind::Gradient, 8, 1.0, 2.0), 0.0625).octaves, 4);
  EXPECT_EQ(octaves_for_footprint(fbm(Kind::Gradient, 8, 1.0, 2.0), 0.125 * (1 + 1e-12)).octaves, 2);
  // The requested maximum is respected even when more octaves would fit.
  c = octaves_for_footprint(fbm(Kind::Gradient, 2, 1.0, 2.0), 1e-6);
  EXPECT_EQ(c.octaves, 2);
  EXPECT_DOUBLE_EQ(c.top_frequency, 2.0);
  // First octave above Nyquist: kept (octaves 1) and flagged.
  c = octaves_for_footprint(fbm(Kind::Gradient, 5, 1.0, 2.0), 1.0);  // Nyquist 0.5 < 1
  EXPECT_EQ(c.octaves, 1);
  EXPECT_TRUE(c.first_aliased);
  EXPECT_DOUBLE_EQ(c.top_frequency, 1.0);
  // Exactly at Nyquist is not aliased.
  c = octaves_for_footprint(fbm(Kind::Gradient, 5, 1.0, 2.0), 0.5);
  EXPECT_FALSE(c.first_aliased);
  EXPECT_EQ(c.octaves, 1);
  // Wavelet: band top 0.5 per lattice unit, frequency 8 -> 4 cycles per unit.
  c = octaves_for_footprint(fbm(Kind::Wavelet, 6, 8.0, 2.0), 1.0 / 64.0);  // Nyquist 32
  EXPECT_EQ(c.octaves, 4);  // 4, 8, 16, 32
  EXPECT_DOUBLE_EQ(c.top_frequency, 32.0);
  // A single noise (Fractal::None) requests one octave.
  NoiseParams single;
  single.kind = Kind::Value;
  single.octaves = 9;  // ignored for Fractal::None
  c = octaves_for_footprint(single, 0.01);
  EXPECT_EQ(c.requested, 1);
  EXPECT_EQ(c.octaves, 1);
}

TEST(NoisePropsFootprint, RandomConfigurationsObeyTheRule) {
  Rng rng(123);
  for (int trial = 0; trial < 20000; ++trial) {
    const Kind kind = Kind(rng.integer(0, 2));
    const int octaves = int(rng.integer(1, kMaxOctaves));
    const double frequency = std::exp(rng.uniform(std::log(1e-3), std::log(1e3)));
    const double lacunarity = rng.uniform(1.05, 4.0);
    const double spacing = std::exp(rng.uniform(std::log(1e-5), std::log(1e2)));
    NoiseParams p = fbm(kind, octaves, frequency, lacunarity);
    if (trial % 4 == 0) p.fractal = Fractal(rng.integer(0, 3));
    const OctaveChoice c = octaves_for_footprint(p, spacing);
    const int requested = p.fractal == Fractal::None ? 1 : octaves;
    const double nyquist = 1.0 / (2.0 * spacing);
    ASSERT_EQ(c.requested, requested);
    ASSERT_GE(c.octaves, 1);
    ASSERT_LE(c.octaves, requested);
    ASSERT_NEAR(c.nyquist, nyquist, 1e-12 * nyquist);
    auto top = [&](int i) { return frequency * std::pow(lacunarity, i) * band_top(kind); };
    // First octave: always kept, flagged iff above Nyquist.
    if (top(0) > nyquist * (1 + 1e-9)) {
      ASSERT_TRUE(c.first_aliased);
    }
    if (top(0) < nyquist * (1 - 1e-9)) {
      ASSERT_FALSE(c.first_aliased);
    }
    // Every kept octave beyond the first fits; the next one (if requested) does not.
    for (int i = 1; i < c.octaves; ++i) ASSERT_LE(top(i), nyquist * (1 + 1e-9)) << "octave " << i;
    if (c.octaves < requested) {
      ASSERT_GT(top(c.octaves), nyquist * (1 - 1e-9));
    }
    ASSERT_NEAR(c.top_frequency, top(c.octaves - 1), 1e-9 * top(c.octaves - 1));
    // limit_octaves applies the same choice.
    OctaveChoice c2;
    const NoiseParams q = limit_octaves(p, spacing, &c2);
    ASSERT_EQ(c2.octaves, c.octaves);
    if (p.fractal != Fractal::None) {
      ASSERT_EQ(q.octaves, c.octaves);
    } else {
      ASSERT_EQ(q.octaves, p.octaves);
    }
  }
}

TEST(NoisePropsFootprint, BadInputsThrow) {
  const NoiseParams p = fbm(Kind::Gradient, 4, 1.0, 2.0);
  for (double s : {0.0, -0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(octaves_for_footprint(p, s), std::invalid_argument) << s;
    EXPECT_THROW(limit_octaves(p, s), std::invalid_argument) << s;
  }
  // Invalid parameters are rejected too.
  NoiseParams bad = p;
  bad.lacunarity = 1.0;
  EXPECT_THROW(octaves_for_footprint(bad, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::noise
