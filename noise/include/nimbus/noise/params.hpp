// What a noise field is: its kind, its fractal sum and their parameters (plain data).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace nimbus::noise {

// Coordinates are in lattice units of the first octave after multiplying by `frequency`.
// Input coordinates are doubles: each octave's lattice cell is found in double precision and
// wrapped to 32 bits before hashing, so the noise near |x| = 2^30 (and beyond, up to 2^50
// lattice units in the highest octave) has the same statistics as near the origin. Float
// inputs would lose the fraction above 2^23 (the float step is 1.0 there).

// Worley: cellular noise 1 - F1 (kernels.hpp), in [1 - sqrt(3), 1], not centred: its mean
// and standard deviation are kWorleyMeanF1 and kWorleySdF1 below.
enum class Kind { Value, Gradient, Wavelet, Worley };

// F1, the distance from a uniform random point to the nearest of one uniform point per unit
// cube cell: mean and standard deviation from a double-precision Monte Carlo of 4e6 samples over
// the 5^3 nearest cells (standard error 1e-4; tests/cpu/test_noise_worley.cpp repeats it
// independently of nimbus's hash).
inline constexpr double kWorleyMeanF1 = 0.5203;
inline constexpr double kWorleySdF1 = 0.1724;
enum class Fractal { None, Fbm, Turbulence, Ridged };

inline constexpr int kMaxOctaves = 24;

struct NoiseParams {
  Kind kind = Kind::Gradient;
  Fractal fractal = Fractal::None;  // None evaluates exactly one octave
  int octaves = 1;                  // 1..kMaxOctaves (ignored for Fractal::None)
  double frequency = 1.0;           // lattice cycles per input unit, first octave
  double lacunarity = 2.0;          // frequency ratio between octaves (> 1)
  double gain = 0.5;                // amplitude ratio between octaves (0, 1]
  uint32_t seed = 0;
  // Animation: when set, the field evolves smoothly with time (4D noise for value and
  // gradient, a B-spline blend of decorrelated tiles for wavelet). Time is in lattice units
  // of the first octave; octave i runs lacunarity^i times faster, like its spatial scale.
  std::optional<double> time;
  // Integer period in lattice units of the first octave on each axis (0: not periodic).
  // Fractal sums need an integer lacunarity to stay periodic. Wavelet noise is periodic with
  // its tile, so a periodic wavelet field needs equal, even periods on all axes (>= 8).
  std::array<int32_t, 3> period{0, 0, 0};
  // Wavelet only: evaluate the 3D noise projected onto the plane through the sample with
  // this normal (Cook & DeRose section 3.4), which keeps 2D slices band-limited.
  bool projected = false;
  std::array<double, 3> normal{0.0, 0.0, 1.0};
  // Wavelet only: tile edge in lattice units (even, 8..512); 0 picks 128 or the period.
  int tile_size = 0;
};

// Throws std::invalid_argument naming the offending parameter.
void validate(const NoiseParams& p);

std::string_view to_string(Kind k);
std::string_view to_string(Fractal f);
std::optional<Kind> parse_kind(std::string_view s);
std::optional<Fractal> parse_fractal(std::string_view s);

// Documented output range of a field: every value lies in [lo, hi].
struct Range {
  float lo;
  float hi;
};

}  // namespace nimbus::noise
