// Shape measures of a generated cloud (cloud_shape.hpp).
#include "support/cloud_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nimbus::test {

CloudMask cloud_mask(const openvdb::FloatGrid& density, double extinction_per_m) {
  if (!(extinction_per_m > 0) || !std::isfinite(extinction_per_m))
    throw std::invalid_argument("cloud_mask: extinction must be finite and > 0");
  if (!density.transform().isLinear() || !density.hasUniformVoxels())
    throw std::invalid_argument("cloud_mask: the grid's voxels must be uniform cubes");
  CloudMask m;
  m.voxel_m = density.voxelSize().x();
  const openvdb::CoordBBox box = density.evalActiveVoxelBoundingBox();
  if (box.empty()) return m;
  const openvdb::Coord d = box.dim();
  if (double(d.x()) * d.y() * d.z() > double(int64_t(1) << 31))
    throw std::invalid_argument("cloud_mask: the cloud's box holds more than 2^31 voxels");
  m.min = box.min();
  m.nx = d.x(), m.ny = d.y(), m.nz = d.z();
  m.cloud.assign(size_t(m.nx) * m.ny * m.nz, 0);
  const float threshold = float(kCloudExtinctionPerM / extinction_per_m);
  for (auto v = density.cbeginValueOn(); v; ++v) {
    if (!(*v >= threshold)) continue;
    const openvdb::Coord c = v.getCoord() - m.min;
    m.cloud[m.index(c.x(), c.y(), c.z())] = 1;
  }
  return m;
}

Bodies cloud_bodies(const CloudMask& m) {
  Bodies b;
  b.label.assign(m.cloud.size(), -1);
  std::vector<size_t> sizes, stack;
  const int64_t sx = 1, sy = m.nx, sz = int64_t(m.nx) * m.ny;
  for (size_t start = 0; start < m.cloud.size(); ++start) {
    if (!m.cloud[start] || b.label[start] >= 0) continue;
    const int32_t id = int32_t(sizes.size());
    size_t count = 0;
    stack.assign(1, start);
    b.label[start] = id;
    while (!stack.empty()) {
      const size_t v = stack.back();
      stack.pop_back();
      ++count;
      const int i = int(v % size_t(m.nx)), j = int((v / size_t(m.nx)) % size_t(m.ny)), k = int(v / size_t(sz));
      const bool ok[6] = {i > 0, i + 1 < m.nx, j > 0, j + 1 < m.ny, k > 0, k + 1 < m.nz};
      const int64_t step[6] = {-sx, sx, -sy, sy, -sz, sz};
      for (int n = 0; n < 6; ++n) {
        if (!ok[n]) continue;
        const size_t w = size_t(int64_t(v) + step[n]);
        if (m.cloud[w] && b.label[w] < 0) {
          b.label[w] = id;
          stack.push_back(w);
        }
      }
    }
    sizes.push_back(count);
    b.total += count;
  }
  // Renumber largest first.
  std::vector<int32_t> order(sizes.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = int32_t(i);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t c) { return sizes[a] > sizes[c]; });
  std::vector<int32_t> rank(sizes.size());
  for (size_t r = 0; r < order.size(); ++r) {
    rank[order[r]] = int32_t(r);
    b.voxels.push_back(sizes[order[r]]);
  }
  for (int32_t& l : b.label)
    if (l >= 0) l = rank[l];
  return b;
}

namespace {

// Per column, the lowest and highest layer of the body (-1 where the column holds none of it).
struct Columns {
  std::vector<int> lo, hi;
};

Columns body_columns(const CloudMask& m, const Bodies& b, int32_t body) {
  Columns c;
  c.lo.assign(size_t(m.nx) * m.ny, -1);
  c.hi.assign(size_t(m.nx) * m.ny, -1);
  for (int k = 0; k < m.nz; ++k)
    for (int j = 0; j < m.ny; ++j)
      for (int i = 0; i < m.nx; ++i) {
        if (b.label[m.index(i, j, k)] != body) continue;
        const size_t col = size_t(j) * m.nx + i;
        if (c.lo[col] < 0) c.lo[col] = k;
        c.hi[col] = k;
      }
  return c;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double x = q * double(v.size() - 1);
  const size_t i = size_t(x);
  const double f = x - double(i);
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

}  // namespace

BaseFlatness base_flatness(const CloudMask& m, const Bodies& b, int32_t body) {
  BaseFlatness r;
  const Columns c = body_columns(m, b, body);
  std::vector<uint8_t> in(c.lo.size());
  int lowest = m.nz, highest = -1;
  for (size_t col = 0; col < c.lo.size(); ++col) {
    in[col] = c.lo[col] >= 0;
    r.footprint_columns += in[col];
    if (in[col]) lowest = std::min(lowest, c.lo[col]), highest = std::max(highest, c.hi[col]);
  }
  if (!r.footprint_columns) return r;
  r.depth_m = double(highest - lowest + 1) * m.voxel_m;
  r.lowest_layer = lowest;
  // The interior: erode the footprint (4-neighbours) by a quarter of its equivalent radius.
  const int rings = std::max(1, int(std::lround(0.25 * std::sqrt(double(r.footprint_columns) / M_PI))));
  for (int pass = 0; pass < rings; ++pass) {
    std::vector<uint8_t> next = in;
    for (int j = 0; j < m.ny; ++j)
      for (int i = 0; i < m.nx; ++i) {
        const size_t col = size_t(j) * m.nx + i;
        if (!in[col]) continue;
        const bool edge = i == 0 || j == 0 || i + 1 == m.nx || j + 1 == m.ny || !in[col - 1] || !in[col + 1] ||
                          !in[col - m.nx] || !in[col + m.nx];
        if (edge) next[col] = 0;
      }
    in.swap(next);
  }
  std::vector<double> base;
  for (size_t col = 0; col < in.size(); ++col)
    if (in[col]) base.push_back(double(c.lo[col]) * m.voxel_m);
  r.interior_columns = base.size();
  if (base.empty()) return r;
  r.base_iqr_m = quantile(base, 0.75) - quantile(base, 0.25);
  return r;
}

TowerAndAnvil tower_and_anvil(const CloudMask& m, const Bodies& b, int32_t body) {
  std::vector<int> xlo(m.nz, m.nx), xhi(m.nz, -1), ylo(m.nz, m.ny), yhi(m.nz, -1);
  int lowest = m.nz, highest = -1;
  for (int k = 0; k < m.nz; ++k)
    for (int j = 0; j < m.ny; ++j)
      for (int i = 0; i < m.nx; ++i) {
        if (b.label[m.index(i, j, k)] != body) continue;
        xlo[k] = std::min(xlo[k], i), xhi[k] = std::max(xhi[k], i);
        ylo[k] = std::min(ylo[k], j), yhi[k] = std::max(yhi[k], j);
        lowest = std::min(lowest, k), highest = std::max(highest, k);
      }
  TowerAndAnvil t;
  if (highest < 0) return t;
  auto width = [&](int k) {
    return xhi[k] < 0 ? 0.0 : double(std::max(xhi[k] - xlo[k], yhi[k] - ylo[k]) + 1) * m.voxel_m;
  };
  const double depth = highest - lowest + 1;
  std::vector<double> tower;
  for (int k = lowest + int(0.1 * depth); k <= lowest + int(0.5 * depth); ++k) tower.push_back(width(k));
  t.tower_width_m = quantile(tower, 0.5);
  for (int k = lowest + int(std::ceil(0.7 * depth)); k <= highest; ++k) t.anvil_width_m = std::max(t.anvil_width_m, width(k));
  return t;
}

}  // namespace nimbus::test
