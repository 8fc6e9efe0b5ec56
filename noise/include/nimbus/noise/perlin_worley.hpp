// Perlin-Worley noise: gradient (Perlin) fBm remapped onto the range left by Worley fBm, the
// billow texture of Schneider's Nubis clouds (Schneider 2015, GPU Pro 7 chapter II-4):
//   P  = clamp(1/2 + fbm_gradient / (4 sd), 0, 1)       +-2 standard deviations onto [0, 1]
//   W  = clamp(fbm_worley, 0, 1)                         1 - F1 summed: 1 at feature points
//   PW = remap(P, 0, 1, W, 1) = W + P (1 - W)            in [W, 1] subset of [0, 1]
// W gives round cells, packed like cauliflower lumps, at every octave; P fills in between
// them with continuous turbulence, so thresholding PW leaves billows rather than blobs.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "nimbus/noise/batch.hpp"
#include "nimbus/noise/field.hpp"

namespace nimbus::noise {

struct PerlinWorleyParams {
  double frequency = 1.0;     // cycles per input unit, first octave of both sums
  int perlin_octaves = 4;     // gradient fBm octaves, [1, 24]
  int worley_octaves = 3;     // Worley fBm octaves, [1, 24]
  double lacunarity = 2.0;    // both sums, (1, 16]
  double gain = 0.5;          // both sums, (0, 1]
  uint32_t seed = 0;          // the Worley sum uses seed + 1
  std::optional<double> time; // lattice units of the first octave, as NoiseParams::time
  std::array<int32_t, 3> period{0, 0, 0};  // as NoiseParams::period
};

class PerlinWorleyField {
 public:
  // Throws std::invalid_argument naming the parameter.
  explicit PerlinWorleyField(const PerlinWorleyParams& p);

  float eval(double x, double y, double z) const;
  // Batched through the SIMD paths of both sums: the same bits as eval at every level.
  void evaluate_points(std::span<const std::array<double, 3>> points, std::span<float> out,
                       const BatchOptions& options = {}) const;

  const NoiseField& perlin() const { return perlin_; }
  const NoiseField& worley() const { return worley_; }
  // The combination, for values computed elsewhere (the eval of each sum).
  float combine(float perlin_fbm, float worley_fbm) const;

 private:
  NoiseField perlin_, worley_;
  float inv_4sd_;
};

NoiseParams perlin_part(const PerlinWorleyParams& p);
NoiseParams worley_part(const PerlinWorleyParams& p);

}  // namespace nimbus::noise
