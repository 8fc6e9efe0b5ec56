// compare_images: relative RMSE, maximum relative error and bias over a reference's lit pixels.
#include "nimbus/render/image/image_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/render/image/image_io.hpp"

namespace nimbus::render {
namespace {

double luminance(const float* px) { return 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2]; }

void check_mask(const ErrorMask& m) {
  if (!(m.lit_fraction >= 0.0 && m.lit_fraction < 1.0)) {
    throw std::invalid_argument("ErrorMask.lit_fraction must be in [0, 1), got " + std::to_string(m.lit_fraction));
  }
  if (!(m.floor_fraction > 0.0 && std::isfinite(m.floor_fraction))) {
    throw std::invalid_argument("ErrorMask.floor_fraction must be > 0, got " + std::to_string(m.floor_fraction));
  }
  if (!(m.percentile > 0.0 && m.percentile <= 1.0)) {
    throw std::invalid_argument("ErrorMask.percentile must be in (0, 1], got " + std::to_string(m.percentile));
  }
}

// The mask's quantile P of the positive reference luminances; 0 when none is positive.
double luminance_scale(const Image& reference, double percentile) {
  std::vector<double> y;
  y.reserve(reference.rgba.size() / 4);
  for (std::size_t i = 0; i < reference.rgba.size(); i += 4) {
    const double l = luminance(&reference.rgba[i]);
    if (l > 0.0) y.push_back(l);
  }
  if (y.empty()) return 0.0;
  const std::size_t rank = static_cast<std::size_t>(std::ceil(percentile * static_cast<double>(y.size())));
  const std::size_t k = std::clamp<std::size_t>(rank, 1, y.size()) - 1;
  std::nth_element(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(k), y.end());
  return y[k];
}

}  // namespace

std::vector<std::uint8_t> lit_pixels(const Image& reference, const ErrorMask& mask) {
  check_mask(mask);
  check_image(reference, "reference image", true);
  const double threshold = mask.lit_fraction * luminance_scale(reference, mask.percentile);
  std::vector<std::uint8_t> lit(reference.rgba.size() / 4, 0);
  for (std::size_t p = 0; p < lit.size(); ++p) lit[p] = luminance(&reference.rgba[4 * p]) > threshold ? 1 : 0;
  return lit;
}

ImageError compare_images(const Image& test, const Image& reference, const ErrorMask& mask) {
  if (test.width != reference.width || test.height != reference.height) {
    throw std::invalid_argument("image sizes differ: test " + std::to_string(test.width) + "x" +
                                std::to_string(test.height) + ", reference " + std::to_string(reference.width) +
                                "x" + std::to_string(reference.height));
  }
  check_image(test, "test image", true);
  const std::vector<std::uint8_t> lit = lit_pixels(reference, mask);
  const double floor = mask.floor_fraction * luminance_scale(reference, mask.percentile);
  double sum_sq_err = 0.0, sum_sq_ref = 0.0, sum_err = 0.0, sum_ref = 0.0;
  ImageError e;
  std::vector<double> pixel_rel;  // per lit pixel: the largest channel's relative error
  for (std::size_t p = 0; p < lit.size(); ++p) {
    if (!lit[p]) continue;
    ++e.pixels;
    double rel = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double t = test.rgba[4 * p + c];
      const double r = reference.rgba[4 * p + c];
      const double d = t - r;
      sum_sq_err += d * d;
      sum_sq_ref += r * r;
      sum_err += d;
      sum_ref += r;
      rel = std::max(rel, std::abs(d) / std::max(std::abs(r), floor));
    }
    e.max_rel = std::max(e.max_rel, rel);
    pixel_rel.push_back(rel);
  }
  if (e.pixels == 0) throw std::invalid_argument("reference image has no lit pixel (all black)");
  e.rel_rmse = std::sqrt(sum_sq_err / sum_sq_ref);
  e.mean_bias = sum_err / sum_ref;
  // Median (upper median for an even count): what a typical lit pixel sees.
  const auto mid = pixel_rel.begin() + static_cast<std::ptrdiff_t>(pixel_rel.size() / 2);
  std::nth_element(pixel_rel.begin(), mid, pixel_rel.end());
  e.median_rel = *mid;
  return e;
}

double noise_corrected_rel_rmse(const Image& test, const Image& reference, const std::vector<float>& reference_std_error,
                                const ErrorMask& mask) {
  const std::size_t n = reference.rgba.size() / 4;
  if (reference_std_error.size() != 3 * n) {
    throw std::invalid_argument("reference standard error: expected 3 values per pixel (" + std::to_string(3 * n) +
                                "), got " + std::to_string(reference_std_error.size()));
  }
  compare_images(test, reference, mask);  // the same checks, sizes and values
  const std::vector<std::uint8_t> lit = lit_pixels(reference, mask);
  double sum_sq_err = 0.0, sum_sq_ref = 0.0, sum_var = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double s = reference_std_error[3 * p + c];
      if (!(s >= 0.0 && std::isfinite(s))) {
        throw std::invalid_argument("reference standard error: pixel (" + std::to_string(p % reference.width) + ", " +
                                    std::to_string(p / reference.width) + ") channel " + "RGB"[c] +
                                    " is negative or not finite");
      }
      if (!lit[p]) continue;
      const double d = double(test.rgba[4 * p + c]) - reference.rgba[4 * p + c];
      sum_sq_err += d * d;
      sum_sq_ref += double(reference.rgba[4 * p + c]) * reference.rgba[4 * p + c];
      sum_var += s * s;
    }
  }
  // The reference's signal must dominate its noise for the ratio to mean anything.
  const double signal = std::max(sum_sq_ref - sum_var, 1e-3 * sum_sq_ref);
  return std::sqrt(std::max(0.0, sum_sq_err - sum_var) / signal);
}

}  // namespace nimbus::render
