// Shared helpers for the noise property tests (tests/cpu/test_noise_props_*.cpp): a fixed
// pseudo-random generator (the same numbers on every platform and standard library),
// random point sets, and moment statistics over large batches evaluated with
// evaluate_points / evaluate_grid.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"

namespace nimbus::test {

// SplitMix64 (Steele, Lea, Flood 2014). std::uniform_real_distribution is not specified
// bit-for-bit across standard libraries, so the tests draw their own numbers.
class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  uint64_t next() {
    uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform multiple of 2^-frac_bits in [lo, hi): exact in double, and it stays exact when an
  // integer below 2^(52 - frac_bits - log2|hi|) is added (used for bit-exact periodicity).
  double dyadic(double lo, double hi, int frac_bits) {
    const double scale = double(uint64_t(1) << frac_bits);
    const double v = lo + std::floor((hi - lo) * scale * uniform()) / scale;
    return v;
  }
  int64_t integer(int64_t lo, int64_t hi) {  // inclusive
    return lo + int64_t(next() % uint64_t(hi - lo + 1));
  }

 private:
  uint64_t s_;
};

// Running moments, in double.
struct Moments {
  int64_t n = 0;
  double sum = 0.0, sum2 = 0.0;
  float min = 0.0f, max = 0.0f;
  int64_t non_finite = 0;
  void add(float v) {
    if (!std::isfinite(v)) {
      ++non_finite;
      return;
    }
    if (n == 0) min = max = v;
    min = v < min ? v : min;
    max = v > max ? v : max;
    sum += v;
    sum2 += double(v) * v;
    ++n;
  }
  void add(const Moments& o);
  double mean() const { return n ? sum / double(n) : 0.0; }
  double sd() const;
  std::string str() const;
};

// Points uniform in the box [lo, hi]^3 (per axis bounds).
std::vector<std::array<double, 3>> random_points(Rng& rng, size_t count,
                                                 const std::array<double, 3>& lo,
                                                 const std::array<double, 3>& hi);

// Evaluates `field` at `total` random points uniform in [lo, hi]^3, in blocks, with
// evaluate_points (parallel, best SIMD level), and returns the moments of the outputs.
Moments random_moments(const noise::NoiseField& field, int64_t total, uint64_t seed,
                       const std::array<double, 3>& lo, const std::array<double, 3>& hi);

// Same, but with a callback per block of (points, values) for extra statistics.
using BlockFn = std::function<void(const std::vector<std::array<double, 3>>&, const std::vector<float>&)>;
Moments random_moments(const noise::NoiseField& field, int64_t total, uint64_t seed,
                       const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                       const BlockFn& per_block);

// Bit pattern of a float (bit-exact comparisons that also tell +0 from -0).
uint32_t bits(float v);

// Short description of a parameter set for failure messages.
std::string describe(const noise::NoiseParams& p);

}  // namespace nimbus::test
