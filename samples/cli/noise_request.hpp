// What `nimbus noise` is asked for, and the noise parameters it makes of it, each bad value a
// UsageError naming its flag. Shared by the command and the Python module (nimbus.noise).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "nimbus/noise/noise.hpp"

namespace nimbus::cli {

struct NoiseOptions {
  std::string kind = "gradient";
  std::string fractal = "none";
  bool projected = false;
  int octaves = 1;
  double frequency = 4.0;  // lattice cycles across the sampled cube, first octave
  double lacunarity = 2.0;
  double gain = 0.5;
  int64_t res = 64;        // samples per axis (the command's; the module checks its own shape)
  uint32_t seed = 0;
  std::optional<double> time;
  int32_t period = 0;
  bool auto_octaves = false;
  std::string simd;
  std::string output;
};

// The field's parameters from everything but res, simd and output: kind, fractal, octaves,
// frequency, lacunarity, gain, seed, time, projection and period, checked.
noise::NoiseParams plan_noise(const NoiseOptions& o);

}  // namespace nimbus::cli
