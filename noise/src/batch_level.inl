// Grid rows and point blocks for NIMBUS_WIDTH lanes; included once per level source file,
// each compiled with its own instruction-set flags.
#include <algorithm>
#include <cstring>
#include <vector>

#include "batch_level.hpp"
#include "kernels.hpp"
#include "point_axes.hpp"
#include "row_axis.hpp"

namespace nimbus::noise::level {
namespace {

using Lanes = simd::Batch<NIMBUS_WIDTH>;

// Rows through the grid's RowAxis: the x axis split once, loaded by every row.
template <class Bt, Kind K, bool Animated>
void rows_from_axis(const detail::FieldData& fd, const GridSpec& g, int64_t r0, int64_t r1, float* out) {
  using F = typename Bt::F;
  constexpr int W = Bt::width;
  const int64_t nx = g.res[0], ny = g.res[1];
  thread_local kernels::RowAxis ra;
  thread_local std::vector<float> cells[kMaxOctaves];        // Worley: the row's cell tables
  thread_local std::vector<uint32_t> lattice[kMaxOctaves];   // value, gradient: the row's tables
  kernels::build_row_axis(fd, g, W, ra);
  const int octaves = fd.fractal == Fractal::None ? 1 : fd.octaves;
  kernels::RowContext rc;
  const double x_lo = g.origin[0], x_hi = g.origin[0] + double(nx - 1) * g.spacing;
  for (int64_t row = r0; row < r1; ++row) {
    const int64_t j = row % ny, k = row / ny;
    kernels::prepare_row<Bt>(fd, g.origin[1] + double(j) * g.spacing,
                             g.origin[2] + double(k) * g.spacing, x_lo, x_hi, rc, nullptr);
    for (int o = 0; o < octaves; ++o) {
      kernels::RowOctave& ro = rc.oct[o];
      ro.wcells = nullptr;
      ro.lcells = nullptr;
      if (!ra.cell_table[o]) continue;
      if constexpr (K == Kind::Worley) {
        kernels::worley_row_cells(fd, ra, o, ro, cells[o]);
        ro.wcells = cells[o].data();
      } else if (W == 1) {
        // Lane groups measured faster hashing their corners than permuting a table's.
        kernels::lattice_row_cells(fd, ra, o, ro, 1, lattice[o], ro.lstride);
        ro.lcells = lattice[o].data();
      }
    }
    float* dst = out + row * nx;
    for (int64_t i = 0; i < nx; i += W) {
      const F v = kernels::field_row_axis<Bt, K, Animated>(fd, ra, i, rc);
      if (nx - i >= W)
        std::memcpy(dst + i, &v, sizeof(F));  // a whole lane group: one store
      else
        std::memcpy(dst + i, &v, sizeof(float) * size_t(nx - i));
    }
  }
}

template <class Bt, Kind K>
void rows_of_kind(const detail::FieldData& fd, const GridSpec& g, int64_t r0, int64_t r1, float* out) {
  if constexpr (K != Kind::Wavelet) {
    if (kernels::row_axis_pays(fd, g, r0, r1)) {
      return fd.animated ? rows_from_axis<Bt, K, true>(fd, g, r0, r1, out)
                         : rows_from_axis<Bt, K, false>(fd, g, r0, r1, out);
    }
  }
  using D = typename Bt::D;
  using F = typename Bt::F;
  constexpr int W = Bt::width;
  const int64_t nx = g.res[0], ny = g.res[1];
  // Row context: y, z and time split once per row and octave (wavelet: column sums).
  thread_local std::vector<float> scratch;
  if (K == Kind::Wavelet) scratch.resize(size_t(kMaxOctaves) * 3 * size_t(fd.tile_n));
  kernels::RowContext rc;
  const double x_lo = g.origin[0], x_hi = g.origin[0] + double(nx - 1) * g.spacing;
  const double last = double(nx - 1);
  D lanes;
  if constexpr (W == 1) {
    lanes = 0.0;
  } else {
    for (int l = 0; l < W; ++l) lanes[l] = double(l);
  }
  for (int64_t row = r0; row < r1; ++row) {
    const int64_t j = row % ny, k = row / ny;
    kernels::prepare_row<Bt>(fd, g.origin[1] + double(j) * g.spacing,
                             g.origin[2] + double(k) * g.spacing, x_lo, x_hi, rc, scratch.data());
    float* dst = out + row * nx;
    for (int64_t i = 0; i < nx; i += W) {
      // x = origin + index * spacing with index = min(i + lane, nx - 1), the same doubles as
      // GridSpec::point (integers below 2^53 are exact).
      D index = simd::splat<D>(double(i)) + lanes;
      if constexpr (W > 1) index = simd::select(index > last, simd::splat<D>(last), index);
      const D x = g.origin[0] + index * g.spacing;
      const F v = kernels::field_row<Bt, K>(fd, x, rc);
      const int64_t n = nx - i < W ? nx - i : W;
      std::memcpy(dst + i, &v, sizeof(float) * size_t(n));
    }
  }
}

template <class Bt>
void rows(const detail::FieldData& fd, const GridSpec& g, int64_t r0, int64_t r1, float* out) {
  switch (fd.kind) {
    case Kind::Value: return rows_of_kind<Bt, Kind::Value>(fd, g, r0, r1, out);
    case Kind::Gradient: return rows_of_kind<Bt, Kind::Gradient>(fd, g, r0, r1, out);
    case Kind::Wavelet: return rows_of_kind<Bt, Kind::Wavelet>(fd, g, r0, r1, out);
    case Kind::Worley: return rows_of_kind<Bt, Kind::Worley>(fd, g, r0, r1, out);
  }
}

template <class Bt, Kind K>
void points_of_kind(const detail::FieldData& fd, const std::array<double, 3>* p, size_t count, float* out) {
  using D = typename Bt::D;
  using F = typename Bt::F;
  constexpr int W = Bt::width;
  for (size_t i = 0; i < count; i += W) {
    D x, y, z;
    if constexpr (W == 1) {
      x = p[i][0];
      y = p[i][1];
      z = p[i][2];
    } else {
      for (int l = 0; l < W; ++l) {
        const size_t il = i + l < count ? i + l : count - 1;
        x[l] = p[il][0];
        y[l] = p[il][1];
        z[l] = p[il][2];
      }
    }
    const F v = kernels::field<Bt, K>(fd, x, y, z);
    if (count - i >= size_t(W))
      std::memcpy(out + i, &v, sizeof(F));
    else
      std::memcpy(out + i, &v, sizeof(float) * (count - i));
  }
}

// Points in blocks: each block's coordinates split first (point_axes.hpp), in lane groups of
// half the width, so the kernel's lane loop holds no double arithmetic. Value, gradient, Worley.
template <class Bt, Kind K>
void points_from_axes(const detail::FieldData& fd, const std::array<double, 3>* p, size_t count, float* out) {
  using F = typename Bt::F;
  using Half = simd::Batch<(NIMBUS_WIDTH > 1 ? NIMBUS_WIDTH / 2 : 1)>;
  constexpr size_t W = size_t(Bt::width);
  constexpr size_t kBlock = kernels::PointAxes::kBlock;
  static_assert(kBlock % W == 0, "a block holds whole lane groups");
  thread_local kernels::PointAxes pa;
  for (size_t b = 0; b < count; b += kBlock) {
    const size_t m = std::min(kBlock, count - b);
    kernels::split_points<Half>(fd, p + b, m, (m + W - 1) / W * W, pa);
    for (size_t i = 0; i < m; i += W) {
      const F v = kernels::fractal_sum<Bt>(fd, [&](const detail::OctaveData& o, int oi) NIMBUS_INLINE_LAMBDA {
        return kernels::octave_from_axes<Bt, K>(fd, o, pa, oi, i);
      });
      if (m - i >= W)
        std::memcpy(out + b + i, &v, sizeof(F));
      else
        std::memcpy(out + b + i, &v, sizeof(float) * (m - i));
    }
  }
}

template <class Bt>
void points(const detail::FieldData& fd, const std::array<double, 3>* p, size_t count, float* out) {
  if (count == 0) return;
  switch (fd.kind) {
    case Kind::Value: return points_from_axes<Bt, Kind::Value>(fd, p, count, out);
    case Kind::Gradient: return points_from_axes<Bt, Kind::Gradient>(fd, p, count, out);
    case Kind::Worley: return points_from_axes<Bt, Kind::Worley>(fd, p, count, out);
    case Kind::Wavelet: return points_of_kind<Bt, Kind::Wavelet>(fd, p, count, out);
  }
}

// points_from_axes for fields on one lattice: each block is split once (the split depends on
// the octaves' frequencies and periods only), then every field sums its octaves from it.
template <class Bt, Kind K>
void shared_points_from_axes(const detail::FieldData* const* fds, size_t nf, const std::array<double, 3>* p,
                             size_t count, float* const* out) {
  using F = typename Bt::F;
  using Half = simd::Batch<(NIMBUS_WIDTH > 1 ? NIMBUS_WIDTH / 2 : 1)>;
  constexpr size_t W = size_t(Bt::width);
  constexpr size_t kBlock = kernels::PointAxes::kBlock;
  thread_local kernels::PointAxes pa;
  for (size_t b = 0; b < count; b += kBlock) {
    const size_t m = std::min(kBlock, count - b);
    kernels::split_points<Half>(*fds[0], p + b, m, (m + W - 1) / W * W, pa);
    for (size_t i = 0; i < m; i += W)
      for (size_t f = 0; f < nf; ++f) {
        const detail::FieldData& fd = *fds[f];
        const F v = kernels::fractal_sum<Bt>(fd, [&](const detail::OctaveData& o, int oi) NIMBUS_INLINE_LAMBDA {
          return kernels::octave_from_axes<Bt, K>(fd, o, pa, oi, i);
        });
        if (m - i >= W)
          std::memcpy(out[f] + b + i, &v, sizeof(F));
        else
          std::memcpy(out[f] + b + i, &v, sizeof(float) * (m - i));
      }
  }
}

template <class Bt>
void shared_points(const detail::FieldData* const* fds, size_t nf, const std::array<double, 3>* p, size_t count,
                   float* const* out) {
  if (count == 0 || nf == 0) return;
  switch (fds[0]->kind) {
    case Kind::Value: return shared_points_from_axes<Bt, Kind::Value>(fds, nf, p, count, out);
    case Kind::Gradient: return shared_points_from_axes<Bt, Kind::Gradient>(fds, nf, p, count, out);
    case Kind::Worley: return shared_points_from_axes<Bt, Kind::Worley>(fds, nf, p, count, out);
    case Kind::Wavelet:  // read from a tile, nothing to split: one field after the other
      for (size_t f = 0; f < nf; ++f) points_of_kind<Bt, Kind::Wavelet>(*fds[f], p, count, out[f]);
      return;
  }
}

}  // namespace

Kernels NIMBUS_LEVEL_FN() { return {&rows<Lanes>, &points<Lanes>, &shared_points<Lanes>}; }

}  // namespace nimbus::noise::level
