// The periodic tile of wavelet-noise coefficients (Cook & DeRose 2005, section 3 and
// appendix 1), built here from the equations rather than the appendix code:
//   r      white noise, unit variance
//   r_c    = U(D(r)) along x, then y, then z: the part of r representable at half resolution,
//            where U refines quadratic B-spline coefficients (mask 1/4, 3/4, 3/4, 1/4) and D is
//            the exact L2 projection onto the half-resolution B-spline space (analysis filter)
//   t      = (r - r_c) + shift(r - r_c, odd offset)   (evens out the parity of the variance)
// The tile is then scaled so that 4 standard deviations map to 1 and clamped to [-1, 1]; since
// the quadratic B-spline weights are >= 0 and sum to 1, wavelet noise lies in [-1, 1].
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

namespace nimbus::noise {

class WaveletTile {
 public:
  // n: tile edge (even, 8..512). Deterministic in (n, seed).
  WaveletTile(int n, uint32_t seed);

  // A tile shared by every field that asks for the same (n, seed) while one is alive.
  static std::shared_ptr<const WaveletTile> shared(int n, uint32_t seed);

  int size() const { return n_; }
  uint32_t seed() const { return seed_; }
  const float* data() const { return data_.data(); }
  float at(int x, int y, int z) const { return data_[(size_t(z) * n_ + y) * n_ + x]; }
  // Factor applied to the band-pass coefficients (unit-variance input) before clamping.
  double scale() const { return scale_; }
  // Standard deviation of the band-pass coefficients before scaling.
  double band_sd() const { return band_sd_; }
  // How many coefficients the clamp to [-1, 1] changed (none so far: the band-pass part of
  // uniform white noise stays within 4 standard deviations).
  int64_t clamped() const { return clamped_; }

 private:
  int n_;
  uint32_t seed_;
  double scale_ = 1.0;
  double band_sd_ = 0.0;
  int64_t clamped_ = 0;
  std::vector<float> data_;
};

// Projected wavelet noise averages along the normal with a quadratic B-spline this many
// lattice units wide per unit (Cook & DeRose use 2; see field.cpp and docs/noise.md).
inline constexpr double kProjectionStretch = 3.0;

// How many standard deviations of the tile map to 1 (the clamp level).
inline constexpr double kWaveletClampSigmas = 4.0;

// Analysis filter of the exact L2 projection onto half-resolution quadratic B-splines, for a
// periodic line of n fine coefficients: coarse[m] = sum_j filter[j] * fine[(2m + j - r) mod n],
// taps[t] applying to offset first + t. For n <= 64 the filter holds all n taps (the exact
// periodic projection); for larger n the taps beyond |j| = 32, all below 3e-6, are dropped.
struct AnalysisFilter {
  std::vector<float> taps;
  int first;  // offset of taps[0] relative to 2m
};
AnalysisFilter wavelet_analysis_filter(int n);

// One line: coarse = D(fine) (n / 2 values), and fine = U(coarse) (n values).
void wavelet_downsample(const float* fine, float* coarse, int n, const AnalysisFilter& f);
void wavelet_upsample(const float* coarse, float* fine, int n);

// The same for `len` lines at once: rows r = 0..n-1 of `len` floats at base + r * stride
// (line x is element x of every row) become U(D(line)). scratch holds (n / 2) * len floats.
void project_rows(float* base, size_t stride, int n, int len, const AnalysisFilter& f,
                  float* scratch);

}  // namespace nimbus::noise
