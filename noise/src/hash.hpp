// Lattice hashing: unsigned 32-bit arithmetic only (wraps, never overflows), the same in
// every lane width.
#pragma once
#include <cstdint>

#ifndef NIMBUS_KERNEL_NS
#define NIMBUS_KERNEL_NS base
#endif

// Each instruction-set level compiles these inline functions into its own namespace, so the
// linker can never hand one level's copy to another.
namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace hash {

// Odd multipliers that spread lattice coordinates over 32 bits before mixing.
inline constexpr uint32_t kPrimeX = 0x8da6b343u;
inline constexpr uint32_t kPrimeY = 0xd8163841u;
inline constexpr uint32_t kPrimeZ = 0xcb1ab31fu;
inline constexpr uint32_t kPrimeW = 0x165667b1u;

// Avalanche mixer (the "lowbias32" constants of C. Wellons' hash-prospector).
template <class U>
constexpr inline __attribute__((always_inline)) U mix(U h) {
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

// Seed of octave i, decorrelated from the seeds of other octaves and other fields.
constexpr uint32_t octave_seed(uint32_t seed, int octave) {
  return mix<uint32_t>(seed * 0x9e3779b9u + static_cast<uint32_t>(octave) * 0x85ebca6bu + 0x27d4eb2fu);
}

}  // namespace hash
}  // inline namespace
}  // namespace nimbus::noise

