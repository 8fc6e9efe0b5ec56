// Worley (cellular) noise kernels, written once over lane types like the rest of kernels.hpp:
// cell axes, feature points, and the search for the nearest point (Worley 1996). Part of
// kernels.hpp, which includes it after the lattice helpers it uses: include kernels.hpp.
#pragma once
#include <cstdint>

namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace kernels {

// One feature point per lattice cell, uniform in the cell and hashed from it (Worley 1996);
// the noise is 1 - F1, F1 the distance to the nearest feature point in lattice units. F1 is
// at most sqrt(3) (the sample's own cell holds a point), so 1 - F1 lies in [1 - sqrt(3), 1].
// Animated: each coordinate of a point moves as a triangle wave tri(phase + v t) of speed
// |v| in {0.5, 0.75, 1, 1.25} cells per time unit, with a uniform phase, so the points stay in
// their cells, move continuously, and are uniform in the cell at every time.

// One axis of a sample: the hashed coordinates of cells c-2 .. c+2 and the fraction t.
template <class B>
struct CellAxis {
  typename B::U h[5];
  typename B::F t;
};

template <class B>
NIMBUS_INLINE CellAxis<B> cell_axis(typename B::D x, double period, int32_t iperiod, uint32_t prime) {
  using D = typename B::D;
  using I = typename B::I;
  using U = typename B::U;
  const D c = floor_exact(x);
  CellAxis<B> a;
  a.t = convert<typename B::F>(x - c);
  if (period > 0.0) {  // cells c + k wrapped into [0, period); two steps each way cover period 1
    const I c0 = bitcast<I>(low_bits<B>(mod_exact(c, period, 1.0 / period)));
    const I p = splat<I>(iperiod);
    for (int k = -2; k <= 2; ++k) {
      I v = c0 + k;
      v = select(v < 0, v + p, v);
      v = select(v < 0, v + p, v);
      v = select(v >= p, v - p, v);
      v = select(v >= p, v - p, v);
      a.h[k + 2] = bitcast<U>(v) * prime;
    }
  } else {
    const U c0 = low_bits<B>(c);
    for (int k = -2; k <= 2; ++k) a.h[k + 2] = (c0 + uint32_t(k)) * prime;
  }
  return a;
}

template <class B, class X>
NIMBUS_INLINE CellAxis<B> cell_axis_any(X x, double period, int32_t iperiod, uint32_t prime) {
  if constexpr (B::width > 1 && std::is_same_v<X, double>) {
    const CellAxis<Batch<1>> a = cell_axis<Batch<1>>(x, period, iperiod, prime);
    CellAxis<B> r;
    for (int k = 0; k < 5; ++k) r.h[k] = splat<typename B::U>(a.h[k]);
    r.t = splat<typename B::F>(a.t);
    return r;
  } else {
    return cell_axis<B>(x, period, iperiod, prime);
  }
}

// A 16-bit hash field as a coordinate in (0, 1).
template <class B>
NIMBUS_INLINE typename B::F unit16(typename B::U bits) {
  using F = typename B::F;
  return (convert<F>(bitcast<typename B::I>(bits & 0xffffu)) + 0.5f) * (1.0f / 65536.0f);
}

// Coordinate of a moving point: tri(2 u + v t), tri(s) = 1 - |1 - (s mod 2)|; `code` holds
// the speed's 2 bits and its sign bit.
template <class B>
NIMBUS_INLINE typename B::F moving(typename B::F u, typename B::U code, float t) {
  using F = typename B::F;
  using I = typename B::I;
  const F speed = (convert<F>(bitcast<I>(code & 3u)) + 2.0f) * 0.25f;
  const F v = bitcast<F>(bitcast<typename B::U>(speed) ^ ((code & 4u) << 29));
  const F s = 2.0f * u + v * t;
  const F m = s - 2.0f * floor_small<F, I>(s * 0.5f);
  return 1.0f - abs(1.0f - m);
}

// The feature point of the cell with hashed coordinates hx, hy, hz: its offset in the cell.
template <class B>
NIMBUS_INLINE void cell_point(typename B::U hx, typename B::U hy, typename B::U hz, uint32_t seed,
                              bool animated, float time, typename B::F* p) {
  using U = typename B::U;
  const U h1 = hash::mix<U>(hx ^ hy ^ hz ^ seed);
  const U h2 = hash::mix<U>(h1 ^ 0x9e3779b9u);
  p[0] = unit16<B>(h1);
  p[1] = unit16<B>(h1 >> 16);
  p[2] = unit16<B>(h2);
  if (animated) {
    p[0] = moving<B>(p[0], h2 >> 16, time);
    p[1] = moving<B>(p[1], h2 >> 19, time);
    p[2] = moving<B>(p[2], h2 >> 22, time);
  }
}

// Squared distance from the sample (fractions t) to the point of cell (dx, dy, dz).
template <class B>
NIMBUS_INLINE typename B::F cell_d2(const CellAxis<B>* a, int dx, int dy, int dz, uint32_t seed,
                                    bool animated, float time) {
  using F = typename B::F;
  F p[3];
  cell_point<B>(a[0].h[dx + 2], a[1].h[dy + 2], a[2].h[dz + 2], seed, animated, time, p);
  const F px = p[0], py = p[1], pz = p[2];
  const F ex = (float(dx) + px) - a[0].t;
  const F ey = (float(dy) + py) - a[1].t;
  const F ez = (float(dz) + pz) - a[2].t;
  return ex * ex + ey * ey + ez * ez;
}

// Lower bound of |e| on one axis for the cell d steps away (d in -2..2), e = (d + p) - t with
// the point's coordinate p in [0, 1] and the sample's fraction t in [0, 1): |e| >= t - 1 - d
// behind the sample, d - t ahead, 0 in its own cell.
template <class F>
NIMBUS_INLINE F axis_gap(F t, int d) {
  if (d < 0) return t + float(-1 - d);
  if (d > 0) return float(d) - t;
  return splat<F>(0.0f);
}

// The cells (dx, dy, dz) of the search, nearest first: the own cell, the 6 faces, the 12 edges,
// the 8 corners, then the 98 cells of the next shell. Visiting near cells first makes the
// running minimum small early, so the bound below skips more of the later cells.
struct CellOffsets {
  int8_t d[125][3];
  int inner;  // the first 27 are the 3x3x3 block
};

constexpr CellOffsets make_cell_offsets() {
  CellOffsets c{};
  int n = 0;
  for (int ring = 0; ring <= 6; ++ring)  // |dx| + |dy| + |dz| for the inner block, then the shell
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int adx = dx < 0 ? -dx : dx, ady = dy < 0 ? -dy : dy, adz = dz < 0 ? -dz : dz;
          const bool inner = adx <= 1 && ady <= 1 && adz <= 1;
          if (inner && adx + ady + adz == ring) {
            c.d[n][0] = int8_t(dx), c.d[n][1] = int8_t(dy), c.d[n][2] = int8_t(dz);
            ++n;
          }
        }
  c.inner = n;  // 27
  for (int dz = -2; dz <= 2; ++dz)
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int adx = dx < 0 ? -dx : dx, ady = dy < 0 ? -dy : dy, adz = dz < 0 ? -dz : dz;
        if (adx <= 1 && ady <= 1 && adz <= 1) continue;
        c.d[n][0] = int8_t(dx), c.d[n][1] = int8_t(dy), c.d[n][2] = int8_t(dz);
        ++n;
      }
  return c;
}

inline constexpr CellOffsets kCellOffsets = make_cell_offsets();

// 1 - F1 from the sample's cell axes. A cell is searched only when, for some lane, the lower
// bound of its squared distance (axis_gap on each axis) is below that lane's nearest point so
// far; the margin covers the rounding of the computed distances, so a skipped cell could never
// have lowered any lane's minimum. The minimum of a set is the same in any order, so each lane
// gets the bits of a search of all 125 cells (the 98 of the outer shell can matter only when F1
// exceeds 1), whatever the lane width. The 27 inner cells are pruned only on the scalar path
// (PruneInner): across lanes the test is taken about half the time, and the mispredicted branch
// costs more than the cell. inner_d2(dx, dy, dz) gives the squared distances of the
// 27 inner cells (cell_d2, or the same values from a row's cell table).
template <bool PruneInner, class B, class InnerD2>
NIMBUS_INLINE typename B::F worley_search(const CellAxis<B>* a, uint32_t seed, bool animated, float time,
                                          InnerD2&& inner_d2) {
  using F = typename B::F;
  F gap2[3][5];
  for (int k = 0; k < 3; ++k)
    for (int d = -2; d <= 2; ++d) {
      const F g = axis_gap(a[k].t, d);
      gap2[k][d + 2] = g * g;
    }
  F best = inner_d2(0, 0, 0);
  auto search = [&](int c) NIMBUS_INLINE_LAMBDA {
    const int dx = kCellOffsets.d[c][0], dy = kCellOffsets.d[c][1], dz = kCellOffsets.d[c][2];
    const F bound = (gap2[0][dx + 2] + gap2[1][dy + 2] + gap2[2][dz + 2]) * 0.9999f;
    return simd::any(bound < best);
  };
#pragma GCC unroll 27
  for (int c = 1; c < 27; ++c)
    if (!PruneInner || search(c)) best = simd::min(best, inner_d2(kCellOffsets.d[c][0], kCellOffsets.d[c][1], kCellOffsets.d[c][2]));
  // The shell begins at least min over axes of (t + 1, 2 - t) >= 1 away: most samples stop here.
  F shell = splat<F>(2.0f);
  for (int k = 0; k < 3; ++k) shell = simd::min(shell, simd::min(a[k].t + 1.0f, 2.0f - a[k].t));
  if (simd::any(best > shell * shell * 0.9999f)) {
    for (int c = kCellOffsets.inner; c < 125; ++c)
      if (search(c))
        best = simd::min(best, cell_d2<B>(a, kCellOffsets.d[c][0], kCellOffsets.d[c][1], kCellOffsets.d[c][2],
                                          seed, animated, time));
  }
  return 1.0f - simd::sqrt(best);
}

template <class B, bool Prune = B::width == 1>
NIMBUS_INLINE typename B::F worley3_cells(const CellAxis<B>* a, uint32_t seed, bool animated, float time) {
  return worley_search<Prune, B>(a, seed, animated, time, [&](int dx, int dy, int dz) NIMBUS_INLINE_LAMBDA {
    return cell_d2<B>(a, dx, dy, dz, seed, animated, time);
  });
}

template <class B, class DY, class DZ>
NIMBUS_INLINE typename B::F worley3(const detail::OctaveData& o, bool animated, typename B::D X, DY Y,
                                    DZ Z) {
  const CellAxis<B> a[3] = {cell_axis<B>(X, o.period[0], o.iperiod[0], hash::kPrimeX),
                            cell_axis_any<B>(Y, o.period[1], o.iperiod[1], hash::kPrimeY),
                            cell_axis_any<B>(Z, o.period[2], o.iperiod[2], hash::kPrimeZ)};
  return worley3_cells<B>(a, o.seed, animated, o.cell_time);
}

}  // namespace kernels
}  // inline namespace
}  // namespace nimbus::noise
