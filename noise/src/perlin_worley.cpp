// Perlin-Worley noise (see perlin_worley.hpp for the formula).
#include "nimbus/noise/perlin_worley.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace nimbus::noise {

NoiseParams perlin_part(const PerlinWorleyParams& p) {
  NoiseParams n;
  n.kind = Kind::Gradient;
  n.fractal = Fractal::Fbm;
  n.octaves = p.perlin_octaves;
  n.frequency = p.frequency;
  n.lacunarity = p.lacunarity;
  n.gain = p.gain;
  n.seed = p.seed;
  n.time = p.time;
  n.period = p.period;
  return n;
}

NoiseParams worley_part(const PerlinWorleyParams& p) {
  NoiseParams n = perlin_part(p);
  n.kind = Kind::Worley;
  n.octaves = p.worley_octaves;
  n.seed = p.seed + 1;
  return n;
}

PerlinWorleyField::PerlinWorleyField(const PerlinWorleyParams& p)
    : perlin_(perlin_part(p)), worley_(worley_part(p)) {
  inv_4sd_ = static_cast<float>(0.25 / perlin_.expected_sd());
}

float PerlinWorleyField::combine(float perlin_fbm, float worley_fbm) const {
  const float P = std::clamp(0.5f + perlin_fbm * inv_4sd_, 0.0f, 1.0f);
  const float W = std::clamp(worley_fbm, 0.0f, 1.0f);
  return W + P * (1.0f - W);
}

float PerlinWorleyField::eval(double x, double y, double z) const {
  return combine(perlin_.eval(x, y, z), worley_.eval(x, y, z));
}

void PerlinWorleyField::evaluate_points(std::span<const std::array<double, 3>> points, std::span<float> out,
                                        const BatchOptions& options) const {
  if (out.size() != points.size()) throw std::invalid_argument("perlin-worley: output size differs from points");
  std::vector<float> w(points.size());
  noise::evaluate_points(perlin_, points, out, options);
  noise::evaluate_points(worley_, points, w, options);
  for (size_t i = 0; i < out.size(); ++i) out[i] = combine(out[i], w[i]);
}

}  // namespace nimbus::noise
