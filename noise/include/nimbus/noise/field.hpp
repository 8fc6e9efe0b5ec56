// NoiseField: one configured noise (kind, fractal sum, seed, time, period), evaluated at
// single points (the scalar path) or in batches (batch.hpp).
#pragma once
#include <memory>
#include <mutex>

#include "nimbus/noise/detail/field_data.hpp"
#include "nimbus/noise/params.hpp"
#include "nimbus/noise/wavelet_tile.hpp"

namespace nimbus::noise {

// Value and spatial gradient (per input unit) at a point.
struct NoiseGradient {
  float value;
  float dx, dy, dz;
};

class NoiseField {
 public:
  // Validates (std::invalid_argument naming the parameter) and, for wavelet noise, builds or
  // shares the coefficient tile.
  explicit NoiseField(const NoiseParams& params);

  const NoiseParams& params() const { return params_; }

  // The scalar path. Identical bits to every SIMD level of evaluate_grid/evaluate_points.
  float eval(double x, double y, double z) const;
  float operator()(double x, double y, double z) const { return eval(x, y, z); }

  // Analytic gradient: value and gradient kinds, not animated. Throws std::logic_error
  // otherwise.
  NoiseGradient eval_gradient(double x, double y, double z) const;

  // Every output lies in range(): [-1, 1] for single noises and fBm, [0, 1] for turbulence
  // and ridged sums.
  Range range() const;

  // Standard deviation predicted from the construction, for Fractal::None and Fbm of
  // non-projected noise (value: lattice variance and interpolation weights; gradient: the
  // gradient set; wavelet: the tile's autocovariance against the B-spline kernel). NaN where
  // no prediction is documented (turbulence, ridged, projected).
  double expected_sd() const;
  // Mean predicted likewise: 0 for value, gradient and wavelet noise and their fBm, and
  // 1 - kWorleyMeanF1 for Worley noise and its fBm (the amplitudes sum to 1).
  double expected_mean() const;

  const WaveletTile* tile() const { return tile_.get(); }
  const detail::FieldData& data() const { return data_; }

 private:
  double single_octave_sd() const;

  NoiseParams params_;
  std::shared_ptr<const WaveletTile> tile_;
  detail::FieldData data_;
  mutable std::once_flag sd_once_;
  mutable double wavelet_var_ = 0.0;
};

// Worley noise: where the feature point of lattice cell (cx, cy, cz) of `octave` lies, in that
// octave's lattice units (the cell's corner plus the float offset the kernels use). For tests
// and tools that check the nearest-point search by brute force. std::invalid_argument for a
// field of another kind or an octave it does not have.
std::array<double, 3> worley_feature_point(const NoiseField& field, int octave, int64_t cx, int64_t cy,
                                           int64_t cz);

// Single-octave helpers on the same kernels (lattice units, period 0).
float value_noise(double x, double y, double z, uint32_t seed = 0);
float value_noise(double x, double y, double z, double t, uint32_t seed);
float gradient_noise(double x, double y, double z, uint32_t seed = 0);
float gradient_noise(double x, double y, double z, double t, uint32_t seed);

// Raw (unscaled) improved-Perlin noise in one cell with chosen gradient indices at its
// corners (corner k has offsets k&1, k>>1&1, k>>2&1, k>>3&1); edge index 0..11 in 3D is
// (pair = i >> 2: xy, xz, yz; sign bits i&1, i&2), 0..31 in 4D. For verifying the bound.
float gradient_noise_cell(const float t[3], const int index[8]);
float gradient_noise_cell4(const float t[4], const int index[16]);
// The gradient vector of edge index i (3D).
void edge_gradient3(int index, float g[3]);

}  // namespace nimbus::noise
