// The x axis of a grid's rows, split once per grid: every row of a GridSpec has the same x
// coordinates, so the hashed lattice (or cell) coordinates and the fraction of each sample and
// octave are computed once, in double precision, and loaded by every row; the row loop then
// holds no double arithmetic. The values are those split() and cell_axis() give per sample.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "kernels.hpp"
#include "nimbus/noise/batch.hpp"

namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace kernels {

struct RowAxis {
  int64_t n = 0;                 // entries per array: the row's samples, padded to whole lane groups
  int slots = 0;                 // hashes per sample: 2 corners (value, gradient) or 5 cells (Worley)
  std::vector<uint32_t> hashes;  // [octave][slot][sample]
  std::vector<float> fracs;      // [octave][sample]
  // Each sample's cell relative to the row's first, and per octave the first cell and
  // how many cells the row spans; a row's cell table (worley_row_cells, lattice_row_cells) pays
  // when a cell holds several samples on average.
  std::vector<int32_t> cells;  // [octave][sample]
  int64_t first_cell[kMaxOctaves] = {};
  int64_t span[kMaxOctaves] = {};
  bool cell_table[kMaxOctaves] = {};

  const uint32_t* hash(int octave, int slot) const {
    return hashes.data() + (size_t(octave) * size_t(slots) + size_t(slot)) * size_t(n);
  }
  const float* frac(int octave) const { return fracs.data() + size_t(octave) * size_t(n); }
  const int32_t* cell(int octave) const { return cells.data() + size_t(octave) * size_t(n); }
};

// Whether a row loop over rows [r0, r1) should use a RowAxis: it pays for itself when more than
// one row shares it, and its size stays that of a few rows of output.
inline bool row_axis_pays(const detail::FieldData& fd, const GridSpec& g, int64_t r0, int64_t r1) {
  return fd.kind != Kind::Wavelet && r1 - r0 >= 2 && g.res[0] <= (int64_t(1) << 16);
}

// Sample i lies at x = origin + min(i, nx - 1) * spacing (GridSpec::point's doubles); octave o
// splits x * freq, as the per-sample path does.
inline void build_row_axis(const detail::FieldData& fd, const GridSpec& g, int width, RowAxis& ra) {
  using B1 = simd::Batch<1>;
  const int64_t nx = g.res[0];
  ra.n = (nx + width - 1) / width * width;
  ra.slots = fd.kind == Kind::Worley ? 5 : 2;
  const int octaves = fd.fractal == Fractal::None ? 1 : fd.octaves;
  ra.hashes.resize(size_t(octaves) * size_t(ra.slots) * size_t(ra.n));
  ra.fracs.resize(size_t(octaves) * size_t(ra.n));
  ra.cells.resize(size_t(octaves) * size_t(ra.n));
  for (int o = 0; o < octaves; ++o) {
    const detail::OctaveData& od = fd.oct[o];
    uint32_t* h = ra.hashes.data() + size_t(o) * size_t(ra.slots) * size_t(ra.n);
    float* t = ra.fracs.data() + size_t(o) * size_t(ra.n);
    for (int64_t i = 0; i < ra.n; ++i) {
      const double X = (g.origin[0] + double(std::min(i, nx - 1)) * g.spacing) * od.freq;
      if (fd.kind == Kind::Worley) {
        const CellAxis<B1> a = cell_axis<B1>(X, od.period[0], od.iperiod[0], hash::kPrimeX);
        for (int s = 0; s < 5; ++s) h[s * ra.n + i] = a.h[s];
        t[i] = a.t;
      } else {
        const Axis<B1> a = split<B1>(X, od.period[0], od.iperiod[0], hash::kPrimeX);
        h[i] = a.h0;
        h[ra.n + i] = a.h1;
        t[i] = a.t;
      }
      // x grows with i, so the first sample's cell is the row's first (|X| < 2^51: exact).
      const auto c = static_cast<int64_t>(floor_exact(X));
      if (i == 0) ra.first_cell[o] = c;
      ra.cells[size_t(o) * size_t(ra.n) + size_t(i)] = int32_t(std::min<int64_t>(c - ra.first_cell[o], 1 << 30));
      ra.span[o] = c - ra.first_cell[o] + 1;
    }
    // A row's table costs 27 cell points (Worley) or 4 to 8 corner hashes (lattice) per cell;
    // a sample without it costs 27 points or 8 to 16 hashes.
    ra.cell_table[o] = (ra.span[o] + 2) * (fd.kind == Kind::Worley ? 4 : 2) <= nx;
  }
}

// A row's lattice table for octave o: for the lattice points m = 0 .. span + 1 along x (the row's
// first cell's lower corner onwards) and each y, z (and time) corner combination j, the mixed
// corner hash mix(hx ^ yzw[j]) that corner_hash gives; `pad` zeros follow each combination, so
// a lane group may load past the end. Layout: [j][m].
inline void lattice_row_cells(const detail::FieldData& fd, const RowAxis& ra, int o, const RowOctave& r,
                              int pad, std::vector<uint32_t>& table, int64_t& stride) {
  using B1 = simd::Batch<1>;
  const detail::OctaveData& od = fd.oct[o];
  const int64_t points = ra.span[o] + 1;
  const int combos = fd.animated ? 8 : 4;
  stride = points + pad;
  table.assign(size_t(combos) * size_t(stride), 0u);
  for (int64_t m = 0; m < points; ++m) {
    // The hashed corners of cell c are split(c).h0 and h1, so lattice point first + m is h0 of
    // its own cell, or h1 of the cell before (which carries the period's wrap).
    const double c = double(ra.first_cell[o] - 1 + m);
    const uint32_t hx = split<B1>(c, od.period[0], od.iperiod[0], hash::kPrimeX).h1;
    for (int j = 0; j < combos; ++j) table[size_t(j) * size_t(stride) + size_t(m)] = hash::mix<uint32_t>(hx ^ r.yzw[j]);
  }
}

// A row's Worley cell table for octave o: for the cells m = 0 .. span + 1 (the row's cells with
// one more on each side) and each (dy, dz) in [-1, 1]^2, the point's x offset px and the terms
// ey^2, ez^2 of its squared distance, which y and z fix for the whole row. The values are
// cell_point's and cell_d2's, so a sample reading them gets the same bits.
inline void worley_row_cells(const detail::FieldData& fd, const RowAxis& ra, int o, const RowOctave& r,
                             std::vector<float>& table) {
  using B1 = simd::Batch<1>;
  const detail::OctaveData& od = fd.oct[o];
  const int64_t cells = ra.span[o] + 2;
  // One spare cell past the last: field_row_axis reads a lane group's first cell and the one after
  // it, and selects the second only for lanes that lie in it, so the group whose lanes all lie in
  // the last cell reads the spare (and never uses it). Without it that read ran past the table
  // (seen as a segfault when the table ended at a page of a thread's heap).
  table.resize(size_t(cells + 1) * 27);
  for (int64_t m = 0; m < cells; ++m) {
    const double c = double(ra.first_cell[o] - 1 + m);
    const uint32_t hx = cell_axis<B1>(c, od.period[0], od.iperiod[0], hash::kPrimeX).h[2];
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        float p[3];
        cell_point<B1>(hx, r.cy.h[dy + 2], r.cz.h[dz + 2], od.seed, fd.animated, od.cell_time, p);
        const float ey = (float(dy) + p[1]) - r.cy.t;
        const float ez = (float(dz) + p[2]) - r.cz.t;
        float* e = table.data() + (size_t(m) * 9 + size_t((dy + 1) * 3 + (dz + 1))) * 3;
        e[0] = p[0];
        e[1] = ey * ey;
        e[2] = ez * ez;
      }
  }
}

// gradient3_faded for 16 lanes along a grid row: edge_dot3's second term, which only the row's
// y and z give, is looked up in the row's vterm table by a lane permute (the 12 gradient
// indices fit one register of 16), instead of a compare, a blend and a sign flip per corner.
// The same values, added in the same order: the same bits.
template <class B>
NIMBUS_INLINE typename B::F gradient3_row16(const typename B::U* idx, typename B::F tx, const RowOctave& r) {
  using F = typename B::F;
  using U = typename B::U;
  using I = typename B::I;
  const F dx[2] = {tx, tx - 1.0f};
  const float dy[2] = {r.y.t, r.y.t - 1.0f};
  F g[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) {
    const int j = k >> 1;
    F u = select(idx[k] >> 2 == 2u, splat<F>(dy[j & 1]), dx[k & 1]);
    u = bitcast<F>(bitcast<U>(u) ^ ((idx[k] & 1u) << 31));
    const F v = __builtin_shuffle(load_lanes<F>(r.vterm[j]), bitcast<I>(idx[k]));
    g[k] = u + v;
  }
  return blend8(g, fade(tx), splat<F>(r.fy), splat<F>(r.fz));
}

// One lane group of a grid row from the grid's RowAxis: the x axis is loaded, y, z and time
// come from the row context; no double arithmetic. Value, gradient and Worley.
template <class B, Kind K, bool Animated, class RowAxisT>
NIMBUS_INLINE typename B::F field_row_axis(const detail::FieldData& fd, const RowAxisT& ra, int64_t i,
                                           const RowContext& rc) {
  using F = typename B::F;
  using U = typename B::U;
  return fractal_sum<B>(fd, [&](const detail::OctaveData& o, int oi) NIMBUS_INLINE_LAMBDA -> F {
    const RowOctave& r = rc.oct[oi];
    const F tx = load_lanes<F>(ra.frac(oi) + i);
    if constexpr (K == Kind::Worley) {
      CellAxis<B> a[3];
      for (int s = 0; s < 5; ++s) {
        a[0].h[s] = load_lanes<U>(ra.hash(oi, s) + i);
        a[1].h[s] = splat<U>(r.cy.h[s]);
        a[2].h[s] = splat<U>(r.cz.h[s]);
      }
      a[0].t = tx;
      a[1].t = splat<F>(r.cy.t);
      a[2].t = splat<F>(r.cz.t);
      if (r.wcells) {
        using I = typename B::I;
        const I k = load_lanes<I>(ra.cell(oi) + i);
        const int32_t k_lo = lane(k, 0), k_hi = lane(k, B::width - 1);  // x grows along the lanes
        if (k_hi - k_lo <= 1) {  // the lanes lie in one or two cells: read the row's table
          const auto first = k == splat<I>(k_lo);
          return worley_search<false, B>(a, o.seed, Animated, o.cell_time,
                                  [&](int dx, int dy, int dz) NIMBUS_INLINE_LAMBDA {
                                    const float* e0 = r.wcells + (size_t(k_lo + 1 + dx) * 9 +
                                                                  size_t((dy + 1) * 3 + (dz + 1))) * 3;
                                    const float* e1 = e0 + 27;
                                    const F px = select(first, splat<F>(e0[0]), splat<F>(e1[0]));
                                    const F ey2 = select(first, splat<F>(e0[1]), splat<F>(e1[1]));
                                    const F ez2 = select(first, splat<F>(e0[2]), splat<F>(e1[2]));
                                    const F ex = (float(dx) + px) - tx;
                                    return ex * ex + ey2 + ez2;
                                  });
        }
      }
      return worley3_cells<B>(a, o.seed, Animated, o.cell_time);
    } else {
      const U hx[2] = {load_lanes<U>(ra.hash(oi, 0) + i), load_lanes<U>(ra.hash(oi, 1) + i)};
      const F ty = splat<F>(r.y.t), tz = splat<F>(r.z.t);
      constexpr int corners = Animated ? 16 : 8;
      U h[corners];
      if constexpr (B::width == 1) {
        if (r.lcells) {  // the scalar path reads its corners' hashes from the row's table
          const uint32_t* e = r.lcells + size_t(ra.cell(oi)[i]);
#pragma GCC unroll 16
          for (int j = 0; j < corners / 2; ++j) {
            h[2 * j] = e[size_t(j) * size_t(r.lstride)];
            h[2 * j + 1] = e[size_t(j) * size_t(r.lstride) + 1];
          }
        }
      }
      if (B::width > 1 || !r.lcells) {
#pragma GCC unroll 16
        for (int k = 0; k < corners; ++k) h[k] = hash::mix<U>(hx[k & 1] ^ r.yzw[k >> 1]);
      }
      if constexpr (Animated) {
        const F tw = splat<F>(r.w.t);
        if constexpr (K == Kind::Value) return value4_cell<B>(h, tx, ty, tz, tw, o.time_norm);
#pragma GCC unroll 16
        for (int k = 0; k < 16; ++k) h[k] = h[k] >> 27;
        return gradient4_cell<B>(h, tx, ty, tz, tw) * kGradientScale4;
      } else {
        if constexpr (K == Kind::Value) return value3_cell<B>(h, tx, ty, tz);
#pragma GCC unroll 16
        for (int k = 0; k < 8; ++k) h[k] = edge_index3(h[k]);
        if constexpr (B::width == 16) return gradient3_row16<B>(h, tx, r) * kGradientScale3;
        return gradient3_faded<B>(h, tx, r.y.t, r.z.t, fade(tx), r.fy, r.fz) * kGradientScale3;
      }
    }
  });
}

}  // namespace kernels
}  // inline namespace
}  // namespace nimbus::noise
