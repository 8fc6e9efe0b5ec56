// Blue-noise dither tiles (Ulichney's void-and-cluster, 1993) for the per-pixel jitter of the
// ray-marched light shafts (thesis 5.1.1): neighbouring pixels get very different offsets, so
// the banding of few steps turns into fine grain instead of white noise's blotches.
#pragma once
#include <cstdint>
#include <vector>

namespace nimbus::render {

// The void-and-cluster rank map of a size x size torus, row-major (index y * size + x): each of
// 0 .. size^2 - 1 exactly once, with a Gaussian energy filter of sigma = 1.5 pixels (toroidal
// distance, truncated at 6 sigma or half the tile). The initial binary pattern holds
// size^2 / 10 pixels chosen from `seed`; equal seeds give equal maps on every platform.
// size must be a power of two in [16, 256] (std::invalid_argument naming "size" otherwise).
std::vector<std::uint32_t> blue_noise_ranks(int size, std::uint32_t seed);

// The same map as thresholds in (0, 1): value = (rank + 0.5) / size^2, each used once, so the
// histogram is exactly uniform.
std::vector<float> blue_noise_tile(int size, std::uint32_t seed);

}  // namespace nimbus::render
