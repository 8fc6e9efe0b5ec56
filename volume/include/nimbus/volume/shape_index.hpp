// Which shapes may be non-zero near a point or box: a 2-D bucket grid over the shapes' boxes,
// so that a field of thousands of clouds costs each voxel a handful of shape tests.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "nimbus/volume/shape.hpp"

namespace nimbus::volume {

class ShapeIndex {
 public:
  explicit ShapeIndex(const std::vector<Shape>& shapes);

  // Calls f(i) for every shape i whose box overlaps `box` (x, y and z); a shape may be visited
  // more than once when the box spans several buckets.
  template <class F>
  void visit(const Aabb& box, F&& f) const {
    if (empty_ || !(box.lo.z < bounds_.hi.z && bounds_.lo.z < box.hi.z)) return;
    const int i0 = cell_x(box.lo.x), i1 = cell_x(box.hi.x), j0 = cell_y(box.lo.y), j1 = cell_y(box.hi.y);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (uint32_t k = start_[size_t(j) * nx_ + i]; k < start_[size_t(j) * nx_ + i + 1]; ++k) {
          const uint32_t s = items_[k];
          if (boxes_[s].overlaps(box)) f(s);
        }
  }
  // The shapes whose box holds p (the only ones with non-zero coverage there).
  template <class F>
  void visit(const glm::dvec3& p, F&& f) const {
    if (empty_) return;
    const size_t c = size_t(cell_y(p.y)) * nx_ + cell_x(p.x);
    for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
      const uint32_t s = items_[k];
      const Aabb& b = boxes_[s];
      if (p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z) f(s);
    }
  }
  bool any_overlaps(const Aabb& box) const {
    bool hit = false;
    visit(box, [&](uint32_t) { hit = true; });
    return hit;
  }
  const Aabb& bounds() const { return bounds_; }

  // Many small boxes in one region: the shapes visit() could visit for any box inside `outer`
  // (each once, in index order), gathered once; visits(box, s) then says, with visit()'s own
  // tests, whether visit(box) visits s. A shape's box is in every bucket it touches, so
  // visit(box) visits exactly the shapes that pass visits(box, s).
  void candidates(const Aabb& outer, std::vector<uint32_t>& out) const;
  bool visits(const Aabb& box, uint32_t s) const {
    return !empty_ && box.lo.z < bounds_.hi.z && bounds_.lo.z < box.hi.z && boxes_[s].overlaps(box);
  }

 private:
  int cell_x(double x) const { return std::clamp(int(std::floor((x - bounds_.lo.x) / cell_)), 0, nx_ - 1); }
  int cell_y(double y) const { return std::clamp(int(std::floor((y - bounds_.lo.y) / cell_)), 0, ny_ - 1); }

  bool empty_ = true;
  Aabb bounds_;
  std::vector<Aabb> boxes_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<uint32_t> start_, items_;  // bucket c holds items_[start_[c] .. start_[c + 1])
};

}  // namespace nimbus::volume
