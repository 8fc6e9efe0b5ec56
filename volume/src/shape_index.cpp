// The shapes' bucket grid (shape_index.hpp).
#include "nimbus/volume/shape_index.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus::volume {

ShapeIndex::ShapeIndex(const std::vector<Shape>& shapes) {
  for (const Shape& s : shapes) {
    boxes_.push_back(shape_bounds(s));
    bounds_ = bounds_.united(boxes_.back());
  }
  empty_ = boxes_.empty() || bounds_.empty();
  if (empty_) return;
  // Buckets about as wide as the median shape, at most 2^20 of them.
  std::vector<double> widths;
  for (const Aabb& b : boxes_) widths.push_back(std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y));
  std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
  const double wx = bounds_.hi.x - bounds_.lo.x, wy = bounds_.hi.y - bounds_.lo.y;
  cell_ = std::max({widths[widths.size() / 2], std::sqrt(wx * wy / double(1 << 20)), 1e-9 * std::max(wx, wy)});
  nx_ = std::max(1, int(std::min(wx / cell_, 4096.0)) + 1);
  ny_ = std::max(1, int(std::min(wy / cell_, 4096.0)) + 1);
  std::vector<uint32_t> count(size_t(nx_) * ny_ + 1, 0);
  auto each = [&](const Aabb& b, auto&& f) {
    for (int j = cell_y(b.lo.y); j <= cell_y(b.hi.y); ++j)
      for (int i = cell_x(b.lo.x); i <= cell_x(b.hi.x); ++i) f(size_t(j) * nx_ + i);
  };
  for (const Aabb& b : boxes_) each(b, [&](size_t c) { ++count[c + 1]; });
  for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  items_.resize(count.back());
  for (uint32_t s = 0; s < boxes_.size(); ++s) each(boxes_[s], [&](size_t c) { items_[count[c]++] = s; });
}

void ShapeIndex::candidates(const Aabb& outer, std::vector<uint32_t>& out) const {
  out.clear();
  visit(outer, [&](uint32_t s) { out.push_back(s); });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace nimbus::volume
