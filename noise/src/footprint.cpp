// Octave selection from the sampling footprint.
#include "nimbus/noise/footprint.hpp"

#include <cmath>
#include <stdexcept>

namespace nimbus::noise {

double band_top(Kind kind) {
  switch (kind) {
    case Kind::Value: return 0.7;
    case Kind::Gradient: return 1.0;
    case Kind::Wavelet: return 0.5;
    case Kind::Worley: return 1.0;  // one feature point per cell: most power near 1 cycle per cell
  }
  return 1.0;
}

OctaveChoice octaves_for_footprint(const NoiseParams& p, double spacing) {
  if (!std::isfinite(spacing) || spacing <= 0.0)
    throw std::invalid_argument("sample spacing must be finite and > 0");
  validate(p);
  OctaveChoice c{};
  c.requested = p.fractal == Fractal::None ? 1 : p.octaves;
  c.nyquist = 0.5 / spacing;
  double top = p.frequency * band_top(p.kind);
  c.first_aliased = top > c.nyquist;
  c.octaves = 1;
  c.top_frequency = top;
  for (int i = 1; i < c.requested; ++i) {
    top *= p.lacunarity;
    if (top > c.nyquist) break;
    c.octaves = i + 1;
    c.top_frequency = top;
  }
  return c;
}

NoiseParams limit_octaves(NoiseParams p, double spacing, OctaveChoice* choice) {
  const OctaveChoice c = octaves_for_footprint(p, spacing);
  if (p.fractal != Fractal::None) p.octaves = c.octaves;
  if (choice) *choice = c;
  return p;
}

}  // namespace nimbus::noise
