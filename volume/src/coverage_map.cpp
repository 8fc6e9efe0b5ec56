// Sampling a coverage map (coverage_map.hpp).
#include "nimbus/volume/coverage_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nimbus::volume {

std::shared_ptr<const CoverageImage> coverage_from_values(std::vector<float> values, int width, int height,
                                                          const std::string& where) {
  if (width < 1 || height < 1 || width > kMaxCoverageMapSide || height > kMaxCoverageMapSide ||
      int64_t(width) * height > kMaxCoverageMapPixels)
    throw std::invalid_argument(where + ": a coverage map must be 1 to " + std::to_string(kMaxCoverageMapSide) +
                                " pixels a side and at most " + std::to_string(kMaxCoverageMapPixels) + " pixels (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  if (values.size() != size_t(width) * size_t(height))
    throw std::invalid_argument(where + ": " + std::to_string(values.size()) + " values for " + std::to_string(width) +
                                " x " + std::to_string(height) + " pixels");
  for (float v : values)
    if (!(v >= 0.0f && v <= 1.0f)) throw std::invalid_argument(where + ": coverage values must be finite and in [0, 1]");
  auto img = std::make_shared<CoverageImage>();
  img->width = width;
  img->height = height;
  img->value = std::move(values);
  img->source = where;
  return img;
}

CoverageMap::CoverageMap(std::shared_ptr<const CoverageImage> image, glm::dvec2 lo_m, glm::dvec2 size_m, bool periodic,
                         bool sets_height)
    : image_(std::move(image)), lo_(lo_m), size_(size_m), periodic_(periodic), sets_height_(sets_height) {
  if (!image_ || image_->width < 1 || image_->height < 1) throw std::invalid_argument("coverage map: no image");
  if (!(std::isfinite(lo_m.x) && std::isfinite(lo_m.y) && size_m.x > 0 && size_m.y > 0 && std::isfinite(size_m.x) &&
        std::isfinite(size_m.y)))
    throw std::invalid_argument("coverage_map_extent: must be finite with east > west and north > south (metres)");
}

double CoverageMap::at(glm::dvec2 p) const {
  const int w = image_->width, h = image_->height;
  // Pixel coordinates with pixel centres at integers: column from the west, row from the north.
  double u = (p.x - lo_.x) / size_.x * w - 0.5;
  double v = (lo_.y + size_.y - p.y) / size_.y * h - 0.5;
  auto axis = [&](double t, int n, int* i0, int* i1, double* f) {
    if (periodic_) {
      const double fl = std::floor(t);
      *f = t - fl;
      const int64_t i = int64_t(fl);
      *i0 = int(((i % n) + n) % n);
      *i1 = (*i0 + 1) % n;
    } else {
      t = std::clamp(t, 0.0, double(n - 1));
      const double fl = std::floor(t);
      *f = t - fl;
      *i0 = int(fl);
      *i1 = std::min(*i0 + 1, n - 1);
    }
  };
  if (!std::isfinite(u) || !std::isfinite(v)) return 0.0;
  int x0, x1, y0, y1;
  double fx, fy;
  axis(u, w, &x0, &x1, &fx);
  axis(v, h, &y0, &y1, &fy);
  const float* px = image_->value.data();
  const double a = px[size_t(y0) * w + x0], b = px[size_t(y0) * w + x1];
  const double c = px[size_t(y1) * w + x0], d = px[size_t(y1) * w + x1];
  const double r = (a + (b - a) * fx) * (1.0 - fy) + (c + (d - c) * fx) * fy;
  return std::clamp(r, 0.0, 1.0);
}

double CoverageMap::mean_over(glm::dvec2 lo, glm::dvec2 size) const {
  constexpr int n = 256;
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) sum += at(lo + glm::dvec2((i + 0.5) / n, (j + 0.5) / n) * size);
  return sum / (double(n) * n);
}

}  // namespace nimbus::volume
