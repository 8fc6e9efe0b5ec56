// Periodic fields repeat bit-exactly: f(p + P e_i) == f(p) for the period P (lattice units of
// the first octave, i.e. P / frequency input units) on every axis, for value and gradient
// noise (single, animated, fBm with integer lacunarity) and for periodic wavelet noise (the
// tile). The same fields without a period do not repeat.
//
// The sample points are multiples of 2^-20 within |x| <= 256, so p + k P is exact in double
// and the comparison tests the noise, not the rounding of the input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::bits;
using test::Rng;

struct PeriodCase {
  std::string name;
  NoiseParams params;
};
void PrintTo(const PeriodCase& c, std::ostream* os) { *os << c.name; }

std::vector<PeriodCase> period_cases() {
  std::vector<PeriodCase> out;
  for (Kind k : {Kind::Value, Kind::Gradient}) {
    const std::string kn = k == Kind::Value ? "Value" : "Gradient";
    NoiseParams p;
    p.kind = k;
    p.seed = 31;
    p.period = {5, 7, 16};
    out.push_back({kn + "Single", p});
    NoiseParams half = p;
    half.frequency = 0.5;  // input periods 10, 14, 32
    out.push_back({kn + "Freq0p5", half});
    NoiseParams anim = p;
    anim.time = 0.3;
    out.push_back({kn + "Animated", anim});
    NoiseParams fbm = p;
    fbm.fractal = Fractal::Fbm;
    fbm.octaves = 4;
    fbm.lacunarity = 2.0;
    out.push_back({kn + "Fbm4", fbm});
    NoiseParams ridged = fbm;
    ridged.fractal = Fractal::Ridged;
    ridged.lacunarity = 3.0;
    ridged.octaves = 3;
    ridged.period = {2, 3, 9};
    out.push_back({kn + "Ridged3Lac3", ridged});
  }
  NoiseParams w;
  w.kind = Kind::Wavelet;
  w.seed = 32;
  w.period = {32, 32, 32};
  out.push_back({"WaveletSingle", w});
  NoiseParams wf = w;
  wf.fractal = Fractal::Fbm;
  wf.octaves = 4;
  out.push_back({"WaveletFbm4", wf});
  NoiseParams wa = w;
  wa.time = 1.7;
  out.push_back({"WaveletAnimated", wa});
  return out;
}

// Input-unit period along `axis`.
double input_period(const NoiseParams& p, int axis) { return double(p.period[axis]) / p.frequency; }

std::vector<std::array<double, 3>> dyadic_points(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<std::array<double, 3>> pts(n);
  for (auto& q : pts)
    for (double& c : q) c = rng.dyadic(-256.0, 256.0, 20);
  return pts;
}

// Counts points where f(p + k * P_axis e_axis) differs in bits from f(p).
int64_t mismatches(const NoiseField& f, const std::vector<std::array<double, 3>>& pts,
                   const std::vector<float>& base, int axis, double shift) {
  std::vector<std::array<double, 3>> moved = pts;
  for (auto& q : moved) q[axis] += shift;
  std::vector<float> out(pts.size());
  evaluate_points(f, moved, out);
  int64_t bad = 0;
  for (size_t i = 0; i < pts.size(); ++i) bad += bits(out[i]) != bits(base[i]);
  return bad;
}

class NoisePropsPeriodic : public ::testing::TestWithParam<PeriodCase> {};

TEST_P(NoisePropsPeriodic, RepeatsBitExactlyOnEveryAxis) {
  const PeriodCase& c = GetParam();
  const NoiseField f(c.params);
  const auto pts = dyadic_points(c.params.kind == Kind::Wavelet && c.params.time ? 20000 : 50000, 8);
  std::vector<float> base(pts.size());
  evaluate_points(f, pts, base);
  for (int axis = 0; axis < 3; ++axis) {
    const double P = input_period(c.params, axis);
    for (int k : {1, -1, 3}) {
      EXPECT_EQ(mismatches(f, pts, base, axis, k * P), 0)
          << test::describe(c.params) << " axis " << axis << " shift " << k * P;
    }
  }
  // The scalar path as well, on a few points.
  for (size_t i = 0; i < 500; ++i) {
    const auto& q = pts[i];
    const float v = f.eval(q[0], q[1], q[2]);
    EXPECT_EQ(bits(v), bits(f.eval(q[0] + input_period(c.params, 0), q[1], q[2])));
    EXPECT_EQ(bits(v), bits(f.eval(q[0], q[1] - input_period(c.params, 1), q[2])));
    EXPECT_EQ(bits(v), bits(f.eval(q[0], q[1], q[2] + 2 * input_period(c.params, 2))));
  }
}

TEST_P(NoisePropsPeriodic, WithoutThePeriodTheFieldDoesNotRepeat) {
  const PeriodCase& c = GetParam();
  NoiseParams p = c.params;
  const std::array<int32_t, 3> period = p.period;
  p.period = {0, 0, 0};
  const NoiseField f(p);
  const auto pts = dyadic_points(5000, 9);
  std::vector<float> base(pts.size());
  evaluate_points(f, pts, base);
  for (int axis = 0; axis < 3; ++axis) {
    const double P = double(period[axis]) / p.frequency;
    // Wavelet noise without a period repeats with its tile (128): 32 is not a multiple.
    const int64_t same = int64_t(pts.size()) - mismatches(f, pts, base, axis, P);
    EXPECT_LT(same, int64_t(pts.size()) / 100) << test::describe(p) << " axis " << axis << " shift " << P;
  }
  // And a periodic field is not periodic with a shorter, non-dividing shift.
  const NoiseField fp(c.params);
  std::vector<float> pbase(pts.size());
  evaluate_points(fp, pts, pbase);
  const int64_t same = int64_t(pts.size()) - mismatches(fp, pts, pbase, 0, input_period(c.params, 0) * 0.5 + 0.25);
  EXPECT_LT(same, int64_t(pts.size()) / 100);
}

INSTANTIATE_TEST_SUITE_P(AllKinds, NoisePropsPeriodic, ::testing::ValuesIn(period_cases()),
                         [](const ::testing::TestParamInfo<PeriodCase>& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace nimbus::noise
