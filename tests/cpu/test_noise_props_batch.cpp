// Batched evaluation: evaluate_grid and evaluate_points give the same bits as
// NoiseField::eval at every SIMD level this CPU supports, for every kind (static and
// animated), fractal sums, periodic and projected fields, odd grid sizes (tail lanes),
// non-zero and large origins, serial and threaded.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <deque>
#include <cstdio>
#include <limits>
#include <span>
#include <ostream>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::bits;
using test::Rng;

std::vector<SimdLevel> supported_levels() {
  std::vector<SimdLevel> out;
  for (SimdLevel l : {SimdLevel::Scalar, SimdLevel::Sse41, SimdLevel::Avx2, SimdLevel::Avx512})
    if (simd_level_supported(l)) out.push_back(l);
  return out;
}

struct BatchCase {
  std::string name;
  NoiseParams params;
};
void PrintTo(const BatchCase& c, std::ostream* os) { *os << c.name; }

std::vector<BatchCase> batch_cases() {
  std::vector<BatchCase> out;
  const std::pair<Kind, const char*> kinds[] = {
      {Kind::Value, "Value"}, {Kind::Gradient, "Gradient"}, {Kind::Wavelet, "Wavelet"}, {Kind::Worley, "Worley"}};
  for (auto [kind, kname] : kinds) {
    const std::string k = kname;
    NoiseParams p;
    p.kind = kind;
    p.seed = 2718;
    p.frequency = 1.37;
    out.push_back({k + "Static", p});
    NoiseParams a = p;
    a.time = 0.3;
    out.push_back({k + "Animated", a});
    a.time = -7.65;
    out.push_back({k + "AnimatedNegativeTime", a});
    // Integer times: the batch paths skip the second time slice (weight 0) except where the
    // first gives +-0, as at lattice points (special_points); eval blends both.
    a.time = 0.0;
    out.push_back({k + "AnimatedTimeZero", a});
    a.time = -3.0;
    out.push_back({k + "AnimatedIntegerTime", a});
    NoiseParams f = p;
    f.fractal = Fractal::Fbm;
    f.octaves = 5;
    f.lacunarity = 2.03;
    out.push_back({k + "Fbm5", f});
    NoiseParams fa = f;
    fa.time = 2.2;
    out.push_back({k + "Fbm5Animated", fa});
    NoiseParams t = f;
    t.fractal = Fractal::Turbulence;
    t.octaves = 3;
    out.push_back({k + "Turbulence3", t});
    NoiseParams r = f;
    r.fractal = Fractal::Ridged;
    r.octaves = 3;
    out.push_back({k + "Ridged3", r});
    NoiseParams per = p;
    per.frequency = 1.0;
    per.fractal = Fractal::Fbm;
    per.octaves = 3;
    per.lacunarity = 2.0;
    per.period = kind == Kind::Wavelet ? std::array<int32_t, 3>{16, 16, 16} : std::array<int32_t, 3>{5, 7, 16};
    out.push_back({k + "PeriodicFbm3", per});
  }
  NoiseParams proj;
  proj.kind = Kind::Wavelet;
  proj.projected = true;
  proj.normal = {0.2, 0.9, -0.4};
  proj.seed = 5;
  out.push_back({"WaveletProjected", proj});
  NoiseParams projf = proj;
  projf.fractal = Fractal::Fbm;
  projf.octaves = 2;
  projf.time = 0.45;
  projf.normal = {0.0, 0.0, 1.0};
  out.push_back({"WaveletProjectedFbm2Animated", projf});
  return out;
}

struct GridCase {
  std::array<double, 3> origin;
  double spacing;
  std::array<int64_t, 3> res;
};

std::vector<GridCase> grids(bool small) {
  std::vector<GridCase> g = {
      {{-3.3, 1.7, 2.9}, 0.173, {37, 5, 3}},          // odd: tail lanes at every width
      {{0.0, 0.0, 0.0}, 0.25, {33, 3, 2}},            // samples on lattice points and faces
      {{-1e6 - 0.3, 5e5 + 0.7, 123.25}, 0.61, {19, 2, 2}},  // far origin
      {{1073741824.5, -1073741824.25, 7.0}, 0.37, {17, 1, 2}},  // near 2^30
      {{5.5, -2.5, 0.125}, 1.0, {1, 1, 1}},           // a single sample
  };
  if (!small) {
    g.push_back({{-20.0, -11.0, 3.0}, 0.29, {64, 16, 4}});  // whole vectors
    // Many samples per cell: grid rows read a table of the row's cells (Worley, and the scalar
    // path's lattice hashes), lane groups within one cell or across two.
    g.push_back({{-2.2, 0.4, 1.1}, 0.02, {83, 3, 2}});
    g.push_back({{0.03, -0.6, 4.7}, 0.004, {150, 2, 1}});
  }
  return g;
}

std::vector<std::array<double, 3>> special_points() {
  Rng rng(8);
  std::vector<std::array<double, 3>> pts;
  for (int i = 0; i < 1001; ++i)  // odd count
    pts.push_back({rng.uniform(-300, 300), rng.uniform(-300, 300), rng.uniform(-300, 300)});
  const double fixed[][3] = {
      {0.0, 0.0, 0.0},   {-0.0, -0.0, -0.0}, {1.0, 2.0, 3.0},  {-1.0, -2.0, -3.0},
      {0.5, -0.5, 0.5},  {-1e-300, 1e-300, 0.0}, {4.0, -0.999999999, 7.000000001},
      {1073741824.25, -1073741824.75, 3.5}, {-2147483648.5, 2147483647.5, 4294967296.25},
      {1e12 + 0.5, -1e12 - 0.5, 0.25}, {std::nextafter(1.0, 0.0), std::nextafter(-1.0, 0.0), 0.5}};
  for (const auto& f : fixed) pts.push_back({f[0], f[1], f[2]});
  return pts;
}

class NoisePropsBatch : public ::testing::TestWithParam<BatchCase> {};

TEST_P(NoisePropsBatch, GridAndPointsMatchScalarEvalAtEveryLevel) {
  const BatchCase& c = GetParam();
  const NoiseField field(c.params);
  const bool slow = c.params.projected;
  const auto levels = supported_levels();
  ASSERT_FALSE(levels.empty());

  for (const GridCase& gc : grids(slow)) {
    GridSpec g;
    g.origin = gc.origin;
    g.spacing = gc.spacing;
    g.res = gc.res;
    std::vector<float> want(size_t(g.count()));
    for (int64_t k = 0, i = 0; k < g.res[2]; ++k)
      for (int64_t j = 0; j < g.res[1]; ++j)
        for (int64_t x = 0; x < g.res[0]; ++x, ++i) {
          const auto p = g.point(x, j, k);
          want[size_t(i)] = field.eval(p[0], p[1], p[2]);
        }
    for (SimdLevel level : levels) {
      for (bool parallel : {false, true}) {
        std::vector<float> got(want.size(), std::numeric_limits<float>::quiet_NaN());
        evaluate_grid(field, g, got, {level, parallel});
        int64_t bad = 0;
        for (size_t i = 0; i < want.size(); ++i) {
          if (bits(got[i]) != bits(want[i]) && ++bad <= 3)
            ADD_FAILURE() << to_string(level) << (parallel ? " parallel" : " serial") << " grid "
                          << g.res[0] << "x" << g.res[1] << "x" << g.res[2] << " sample " << i
                          << ": " << got[i] << " vs eval " << want[i] << " (" << test::describe(c.params) << ")";
        }
        EXPECT_EQ(bad, 0) << to_string(level);
      }
    }
  }

  auto pts = special_points();
  if (slow) pts.resize(203);
  std::vector<float> want(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) want[i] = field.eval(pts[i][0], pts[i][1], pts[i][2]);
  for (SimdLevel level : levels) {
    for (bool parallel : {false, true}) {
      std::vector<float> got(pts.size(), std::numeric_limits<float>::quiet_NaN());
      evaluate_points(field, pts, got, {level, parallel});
      int64_t bad = 0;
      for (size_t i = 0; i < pts.size(); ++i) {
        if (bits(got[i]) != bits(want[i]) && ++bad <= 3)
          ADD_FAILURE() << to_string(level) << " point (" << pts[i][0] << ", " << pts[i][1] << ", "
                        << pts[i][2] << "): " << got[i] << " vs eval " << want[i];
      }
      EXPECT_EQ(bad, 0) << to_string(level);
      // Every prefix length 1..W+1 (tails of each width) as well.
      for (size_t len = 1; len <= 17 && !slow; ++len) {
        std::vector<float> part(len);
        evaluate_points(field, std::span(pts).subspan(pts.size() - len), part, {level, parallel});
        for (size_t i = 0; i < len; ++i)
          ASSERT_EQ(bits(part[i]), bits(want[pts.size() - len + i])) << to_string(level) << " len " << len;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, NoisePropsBatch, ::testing::ValuesIn(batch_cases()),
                         [](const ::testing::TestParamInfo<BatchCase>& param_info) { return param_info.param.name; });

// Several fields at the same points: fields on one lattice (seeds, gains and times differ) are
// split once, and each must still get its own evaluate_points bits at every level, serial and
// threaded, in whole lane groups and in tails; a set that is not on one lattice falls back to
// one field after the other, with the same bits.
TEST(NoisePropsBatchShared, FieldsOnOneLatticeGiveEachFieldsOwnBits) {
  auto pts = special_points();
  for (Kind kind : {Kind::Value, Kind::Gradient, Kind::Worley, Kind::Wavelet}) {
    std::deque<NoiseField> fields;  // NoiseField does not move
    for (int f = 0; f < 3; ++f) {
      NoiseParams p;
      p.kind = kind;
      p.fractal = Fractal::Fbm;
      p.octaves = 3;
      p.frequency = 0.37;
      p.gain = 0.5 + 0.1 * f;
      p.seed = 11u + uint32_t(f);
      if (f < 2) p.time = 1.3 + 1.7 * f;  // two animated, one static
      fields.emplace_back(p);
    }
    NoiseParams other = fields[0].params();
    other.frequency = 0.41;
    fields.emplace_back(other);
    EXPECT_EQ(shares_lattice(fields[0], fields[1]), kind != Kind::Wavelet) << int(kind);
    EXPECT_EQ(shares_lattice(fields[0], fields[2]), kind != Kind::Wavelet) << int(kind);
    EXPECT_FALSE(shares_lattice(fields[0], fields[3])) << "another frequency is another lattice";

    std::vector<std::vector<float>> want(fields.size(), std::vector<float>(pts.size()));
    for (size_t f = 0; f < fields.size(); ++f) evaluate_points(fields[f], pts, want[f], {SimdLevel::Scalar, false});
    for (size_t nf : {size_t(3), size_t(4)}) {  // one lattice; and with a stranger
      std::vector<const NoiseField*> set;
      for (size_t f = 0; f < nf; ++f) set.push_back(&fields[f]);
      for (SimdLevel level : supported_levels())
        for (bool parallel : {false, true})
          for (size_t len : {pts.size(), size_t(1), size_t(7), size_t(17)}) {
            const auto part = std::span(pts).subspan(pts.size() - len);
            std::vector<std::vector<float>> got(nf, std::vector<float>(len, std::numeric_limits<float>::quiet_NaN()));
            std::vector<std::span<float>> outs(got.begin(), got.end());
            evaluate_points(set, part, outs, {level, parallel});
            for (size_t f = 0; f < nf; ++f)
              for (size_t i = 0; i < len; ++i)
                ASSERT_EQ(bits(got[f][i]), bits(want[f][pts.size() - len + i]))
                    << to_string(level) << " kind " << int(kind) << " field " << f << " of " << nf << ", " << len
                    << " points, point " << i;
          }
    }
  }

  NoiseParams p;
  const NoiseField f(p);
  std::vector<float> a(pts.size()), b(pts.size()), short_out(pts.size() - 1);
  const std::vector<const NoiseField*> two{&f, &f}, with_null{&f, nullptr};
  EXPECT_THROW(evaluate_points(two, pts, std::vector<std::span<float>>{a}), std::invalid_argument);
  EXPECT_THROW(evaluate_points(two, pts, std::vector<std::span<float>>{a, short_out}), std::invalid_argument);
  EXPECT_THROW(evaluate_points(with_null, pts, std::vector<std::span<float>>{a, b}), std::invalid_argument);
}

TEST(NoisePropsBatchLevels, ReportsLevels) {
  std::string s;
  for (SimdLevel l : supported_levels()) s += std::string(to_string(l)) + " ";
  std::printf("SIMD levels tested: %s(best: %s)\n", s.c_str(), std::string(to_string(best_simd_level())).c_str());
  RecordProperty("levels", s);
  EXPECT_TRUE(simd_level_supported(SimdLevel::Scalar));
  for (SimdLevel l : {SimdLevel::Scalar, SimdLevel::Sse41, SimdLevel::Avx2, SimdLevel::Avx512}) {
    EXPECT_EQ(parse_simd_level(to_string(l)), l);
    if (!simd_level_supported(l)) {
      NoiseParams p;
      const NoiseField f(p);
      std::vector<float> out(1);
      GridSpec g;
      EXPECT_THROW(evaluate_grid(f, g, out, {l, false}), std::invalid_argument);
    }
  }
  EXPECT_FALSE(parse_simd_level("avx3").has_value());
}

TEST(NoisePropsBatchErrors, BadShapesThrow) {
  NoiseParams p;
  const NoiseField f(p);
  GridSpec g;
  g.res = {4, 3, 2};
  std::vector<float> small(23), right(24);
  EXPECT_THROW(evaluate_grid(f, g, small), std::invalid_argument);
  EXPECT_NO_THROW(evaluate_grid(f, g, right));
  g.spacing = 0.0;
  EXPECT_THROW(evaluate_grid(f, g, right), std::invalid_argument);
  g.spacing = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(evaluate_grid(f, g, right), std::invalid_argument);
  g.spacing = 1.0;
  g.res = {0, 3, 2};
  std::vector<float> none;
  EXPECT_THROW(evaluate_grid(f, g, none), std::invalid_argument);
  std::vector<std::array<double, 3>> pts(5);
  std::vector<float> four(4);
  EXPECT_THROW(evaluate_points(f, pts, four), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::noise
