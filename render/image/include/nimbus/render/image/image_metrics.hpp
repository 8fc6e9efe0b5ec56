// Image error against a reference over its lit pixels: the numbers `nimbus bench shafts` and
// the renderer tests quote (relative RMSE, maximum relative error, mean bias).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

// Which pixels count, and the floor of the relative error. With Y = 0.2126 R + 0.7152 G +
// 0.0722 B (Rec. 709 luminance) of the reference and P = the `percentile` quantile of Y over
// the reference pixels with Y > 0 (nearest rank: the ceil(percentile * n)-th smallest of n):
//   lit pixel:  Y > lit_fraction * P
//   floor:      floor_fraction * P
// P ignores black pixels so that a mostly black image still has a scale, and is a quantile
// rather than the maximum so that a few hot pixels (a light source seen directly) do not
// decide which fog pixels count.
struct ErrorMask {
  double lit_fraction = 1e-3;    // in [0, 1)
  double floor_fraction = 1e-2;  // > 0
  double percentile = 0.99;      // in (0, 1]
};

// Over the lit pixels' R, G and B channels (alpha is not compared), t = test, r = reference:
//   rel_rmse  = sqrt(sum (t - r)^2 / sum r^2)
//   max_rel   = max |t - r| / max(|r|, floor)
//   mean_bias = sum (t - r) / sum r             (signed: > 0 means the test is too bright)
//   median_rel = median over lit pixels of max over R, G, B of |t - r| / max(|r|, floor)
//               (robust: what a typical pixel sees, where rel_rmse and max_rel follow the worst)
//   pixels    = how many lit pixels
struct ImageError {
  double rel_rmse = 0.0;
  double max_rel = 0.0;
  double mean_bias = 0.0;
  double median_rel = 0.0;
  std::size_t pixels = 0;
};

// 1 for each lit pixel of `reference` (row-major, row 0 at the top), else 0.
std::vector<std::uint8_t> lit_pixels(const Image& reference, const ErrorMask& mask = {});

// Throws std::invalid_argument when the sizes differ (naming both), either image holds NaN or
// Inf (naming which image, the pixel and the channel), a mask field is out of range (naming
// it), or the reference has no lit pixel.
ImageError compare_images(const Image& test, const Image& reference, const ErrorMask& mask = {});

// compare_images' rel_rmse with a noisy reference's own variance taken out. A Monte Carlo
// reference r = mu + e, with E[e] = 0 and Var e = s^2 (s: its standard error per pixel and
// channel, e.g. PathTracedImage::std_error), has E[(t - r)^2] = (t - mu)^2 + s^2 and
// E[r^2] = mu^2 + s^2, so over the lit pixels' R, G, B
//   sqrt(max(0, sum (t - r)^2 - sum s^2) / (sum r^2 - sum s^2))
// estimates the error against the converged reference mu: the part of the RMSE that more
// samples in the reference would not remove. Same throws as compare_images, and
// std::invalid_argument when `reference_std_error` is not 3 per pixel, negative or not finite.
double noise_corrected_rel_rmse(const Image& test, const Image& reference, const std::vector<float>& reference_std_error,
                                const ErrorMask& mask = {});

}  // namespace nimbus::render
