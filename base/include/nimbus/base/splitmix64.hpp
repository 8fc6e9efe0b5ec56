// splitmix64 (Steele, Lea & Flood 2014): a small, fully specified generator, so that layouts,
// jitter tiles and photon paths are the same on every platform (the std distributions are not
// specified bit for bit).
#pragma once
#include <cstdint>

namespace nimbus {

struct SplitMix64 {
  std::uint64_t state = 0;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1), 53 bits
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

}  // namespace nimbus
