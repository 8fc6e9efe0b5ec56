// Precomputed per-octave constants shared by the scalar and SIMD kernels (internal).
#pragma once
#include <cstdint>

#include "nimbus/noise/params.hpp"

namespace nimbus::noise::detail {

struct OctaveData {
  double freq = 1.0;              // lattice cycles per input unit
  double time = 0.0;              // this octave's time coordinate (animated fields)
  float time_norm = 1.0f;         // animated value noise: variance normalisation at `time`
  float cell_time = 0.0f;         // animated Worley noise: `time` modulo 8 (its points' period)
  float amp = 1.0f;               // amplitude in the fractal sum
  uint32_t seed = 0;              // lattice hash seed (value, gradient)
  double period[3] = {0, 0, 0};   // lattice period of this octave (0: none)
  int32_t iperiod[3] = {0, 0, 0};
  // Wavelet: one tile slice, or three B-spline-weighted slices over time.
  int slices = 1;
  float slice_weight[3] = {1.0f, 0.0f, 0.0f};
  int32_t slice_offset[3][3] = {};  // integer lattice offsets in [0, tile_n)
};

struct FieldData {
  Kind kind = Kind::Gradient;
  Fractal fractal = Fractal::None;
  bool animated = false;
  int octaves = 1;
  float inv_amp_sum = 1.0f;
  OctaveData oct[kMaxOctaves];
  const float* tile = nullptr;  // wavelet coefficients, x fastest, tile_n^3
  int32_t tile_n = 0;
  bool projected = false;
  double normal[3] = {0.0, 0.0, 1.0};
};

}  // namespace nimbus::noise::detail
