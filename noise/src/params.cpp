// Validation and names of noise parameters.
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/noise/params.hpp"

namespace nimbus::noise {
namespace {
[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }
std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

void validate(const NoiseParams& p) {
  if (p.fractal != Fractal::None && (p.octaves < 1 || p.octaves > kMaxOctaves))
    bad("octaves " + std::to_string(p.octaves) + " out of range [1, " + std::to_string(kMaxOctaves) + "]");
  if (!std::isfinite(p.frequency) || p.frequency <= 0.0 || p.frequency > 1e12)
    bad("frequency " + num(p.frequency) + " must be finite and in (0, 1e12]");
  if (!std::isfinite(p.lacunarity) || p.lacunarity <= 1.0 || p.lacunarity > 16.0)
    bad("lacunarity " + num(p.lacunarity) + " must be in (1, 16]");
  if (!std::isfinite(p.gain) || p.gain <= 0.0 || p.gain > 1.0)
    bad("gain " + num(p.gain) + " must be in (0, 1]");
  if (p.time && !std::isfinite(*p.time)) bad("time must be finite");
  if (p.time && std::fabs(*p.time) > 1e15) bad("time " + num(*p.time) + " beyond 1e15");
  const bool periodic = p.period[0] > 0 || p.period[1] > 0 || p.period[2] > 0;
  for (int a = 0; a < 3; ++a)
    if (p.period[a] < 0 || p.period[a] > (1 << 30))
      bad("period " + std::to_string(p.period[a]) + " must be in [0, 2^30]");
  if (periodic && p.fractal != Fractal::None && p.lacunarity != std::floor(p.lacunarity))
    bad("a periodic fractal sum needs an integer lacunarity (got " + num(p.lacunarity) + ")");
  if (periodic && p.fractal != Fractal::None) {
    double ratio = std::pow(p.lacunarity, p.octaves - 1);
    for (int a = 0; a < 3; ++a)
      if (p.period[a] > 0 && p.period[a] * ratio > 2147483647.0)
        bad("period times lacunarity^(octaves-1) exceeds 2^31");
  }
  if (p.kind == Kind::Wavelet) {
    if (periodic) {
      if (p.period[0] != p.period[1] || p.period[1] != p.period[2])
        bad("periodic wavelet noise needs the same period on all axes (its tile)");
      if (p.period[0] % 2 != 0 || p.period[0] < 8 || p.period[0] > 512)
        bad("wavelet period " + std::to_string(p.period[0]) + " must be even and in [8, 512]");
      if (p.tile_size != 0 && p.tile_size != p.period[0])
        bad("wavelet tile size must equal the period");
    }
    if (p.tile_size != 0 && (p.tile_size % 2 != 0 || p.tile_size < 8 || p.tile_size > 512))
      bad("wavelet tile size " + std::to_string(p.tile_size) + " must be even and in [8, 512]");
  } else if (p.projected) {
    bad("projected evaluation exists for wavelet noise only");
  }
  if (p.projected) {
    const double l2 = p.normal[0] * p.normal[0] + p.normal[1] * p.normal[1] + p.normal[2] * p.normal[2];
    if (!std::isfinite(l2) || l2 < 1e-12) bad("projection normal must be finite and non-zero");
  }
}

std::string_view to_string(Kind k) {
  switch (k) {
    case Kind::Value: return "value";
    case Kind::Gradient: return "gradient";
    case Kind::Wavelet: return "wavelet";
    case Kind::Worley: return "worley";
  }
  return "?";
}

std::string_view to_string(Fractal f) {
  switch (f) {
    case Fractal::None: return "none";
    case Fractal::Fbm: return "fbm";
    case Fractal::Turbulence: return "turbulence";
    case Fractal::Ridged: return "ridged";
  }
  return "?";
}

std::optional<Kind> parse_kind(std::string_view s) {
  for (Kind k : {Kind::Value, Kind::Gradient, Kind::Wavelet, Kind::Worley})
    if (s == to_string(k)) return k;
  return std::nullopt;
}

std::optional<Fractal> parse_fractal(std::string_view s) {
  for (Fractal f : {Fractal::None, Fractal::Fbm, Fractal::Turbulence, Fractal::Ridged})
    if (s == to_string(f)) return f;
  return std::nullopt;
}

}  // namespace nimbus::noise
