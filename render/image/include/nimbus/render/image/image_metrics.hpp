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

}  // namespace nimbus::render
