// The noise parameters of a noise request (noise_request.hpp).
#include "noise_request.hpp"

#include <cmath>

#include "cli.hpp"

namespace nimbus::cli {

noise::NoiseParams plan_noise(const NoiseOptions& o) {
  noise::NoiseParams p;
  const auto kind = noise::parse_kind(o.kind);
  if (!kind) throw UsageError("--kind: unknown noise kind '" + o.kind + "' (value, gradient, wavelet, worley)");
  const auto fractal = noise::parse_fractal(o.fractal);
  if (!fractal)
    throw UsageError("--fractal: unknown fractal '" + o.fractal + "' (none, fbm, turbulence, ridged)");
  if (!std::isfinite(o.frequency) || o.frequency <= 0.0)
    throw UsageError("--frequency: must be finite and > 0");
  if (o.octaves < 1 || o.octaves > noise::kMaxOctaves)
    throw UsageError("--octaves: " + std::to_string(o.octaves) + " must be in [1, " +
                     std::to_string(noise::kMaxOctaves) + "]");
  if (*fractal == noise::Fractal::None && o.octaves != 1)
    throw UsageError("--octaves: more than one octave needs --fractal fbm, turbulence or ridged");
  if (o.projected && *kind != noise::Kind::Wavelet) throw UsageError("--projected: only for --kind wavelet");
  p.kind = *kind;
  p.fractal = *fractal;
  p.octaves = o.octaves;
  p.frequency = o.frequency;
  p.lacunarity = o.lacunarity;
  p.gain = o.gain;
  p.seed = o.seed;
  p.time = o.time;
  p.projected = o.projected;
  p.period = {o.period, o.period, o.period};
  try {
    noise::validate(p);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return p;
}

}  // namespace nimbus::cli
