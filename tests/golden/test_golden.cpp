// Determinism: FNV-1a hashes of 64^3 grids of every kind must equal the golden values below in
// every build (this file is compiled twice: against the -O2 library and against the same
// sources built -O3 -march=native) and at every SIMD level the CPU supports. A change of
// the noise functions changes these values on purpose; regenerate them with
// NIMBUS_PRINT_GOLDEN=1 and say why in the commit.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"

namespace {

using namespace nimbus::noise;

uint64_t fnv1a(const std::vector<float>& v) {
  uint64_t h = 1469598103934665603ull;
  const auto* b = reinterpret_cast<const unsigned char*>(v.data());
  for (size_t i = 0; i < v.size() * sizeof(float); ++i) {
    h ^= b[i];
    h *= 1099511628211ull;
  }
  return h;
}

struct Case {
  const char* name;
  NoiseParams params;
  int res;
  uint64_t golden;
};

NoiseParams make(Kind k, Fractal f = Fractal::None, int octaves = 1) {
  NoiseParams p;
  p.kind = k;
  p.fractal = f;
  p.octaves = octaves;
  p.seed = 1234;
  p.frequency = 0.37;  // grid spacing 1 input unit: 0.37 lattice units per sample
  return p;
}

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"value", make(Kind::Value), 64, 0});
  c.push_back({"gradient", make(Kind::Gradient), 64, 0});
  c.push_back({"wavelet", make(Kind::Wavelet), 64, 0});
  NoiseParams a = make(Kind::Value);
  a.time = 2.71;
  c.push_back({"value_animated", a, 64, 0});
  a.kind = Kind::Gradient;
  c.push_back({"gradient_animated", a, 64, 0});
  a.kind = Kind::Wavelet;
  c.push_back({"wavelet_animated", a, 64, 0});
  c.push_back({"gradient_fbm6", make(Kind::Gradient, Fractal::Fbm, 6), 64, 0});
  c.push_back({"value_turbulence6", make(Kind::Value, Fractal::Turbulence, 6), 64, 0});
  c.push_back({"wavelet_ridged6", make(Kind::Wavelet, Fractal::Ridged, 6), 64, 0});
  NoiseParams per = make(Kind::Gradient, Fractal::Fbm, 3);
  per.period = {5, 7, 16};
  c.push_back({"gradient_periodic_fbm3", per, 64, 0});
  NoiseParams proj = make(Kind::Wavelet);
  proj.projected = true;
  c.push_back({"wavelet_projected", proj, 16, 0});
  return c;
}

// Golden values, in the order of cases().
constexpr uint64_t kGolden[] = {
    0x633c039f56bc4b4cull,  // value
    0xf4453710aa861354ull,  // gradient
    0x9156990048afbbb9ull,  // wavelet
    0xca64ca3883ad3c16ull,  // value_animated
    0x99cd565aa7284406ull,  // gradient_animated
    0xfad22c2e92440c1aull,  // wavelet_animated
    0x85db8c63b8538875ull,  // gradient_fbm6
    0x8b2fecebc79858ecull,  // value_turbulence6
    0xf3545b1aac259a11ull,  // wavelet_ridged6
    0xb75fbec904f1366bull,  // gradient_periodic_fbm3
    0x1a19af18d3700915ull,  // wavelet_projected
};

TEST(Golden, HashesAreTheSameInEveryBuildAndAtEverySimdLevel) {
  const bool print = std::getenv("NIMBUS_PRINT_GOLDEN") != nullptr;
  const auto all = cases();
  size_t i = 0;
  for (const Case& c : all) {
    const NoiseField field(c.params);
    GridSpec g;
    g.origin = {-3.1, 2.7, 0.3};
    g.spacing = 1.0;
    g.res = {c.res, c.res, c.res};
    std::vector<float> ref(size_t(g.count()));
    evaluate_grid(field, g, ref, {SimdLevel::Scalar, true});
    const uint64_t h = fnv1a(ref);
    if (print) std::printf("    0x%016llxull,  // %s\n", static_cast<unsigned long long>(h), c.name);
    if (!print) {
      ASSERT_LT(i, std::size(kGolden)) << "no golden value for " << c.name;
      EXPECT_EQ(h, kGolden[i]) << c.name;
    }
    for (SimdLevel l : {SimdLevel::Sse41, SimdLevel::Avx2, SimdLevel::Avx512}) {
      if (!simd_level_supported(l)) continue;
      std::vector<float> out(size_t(g.count()));
      evaluate_grid(field, g, out, {l, true});
      EXPECT_EQ(fnv1a(out), h) << c.name << " at " << to_string(l);
    }
    ++i;
  }
}

}  // namespace
