// The split coordinates of a block of points, computed before the lane loop: for each point,
// octave and axis, the hashed lattice corners (value, gradient) or cells c-2 .. c+2 (Worley)
// and the fraction, as split() and cell_axis() give them. The double-precision work runs in lane
// groups of half the width (one register of doubles), apart from the float kernel, which then
// loads its inputs; the bits are those of splitting in the kernel.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "kernels.hpp"

namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace kernels {

struct PointAxes {
  static constexpr size_t kBlock = 256;  // points per block
  int slots = 0;                         // hashes per axis: 2 corners or 5 cells
  std::vector<uint32_t> hashes;          // [octave][axis][slot][point]
  std::vector<float> fracs;              // [octave][axis][point]
  alignas(64) double coords[3][kBlock];  // the block's points by axis, padded with the last

  const uint32_t* hash(int octave, int axis, int slot) const {
    return hashes.data() + ((size_t(octave) * 3 + size_t(axis)) * size_t(slots) + size_t(slot)) * kBlock;
  }
  const float* frac(int octave, int axis) const {
    return fracs.data() + (size_t(octave) * 3 + size_t(axis)) * kBlock;
  }
};

// Splits points [0, count) of p (count <= kBlock; the block is padded to whole lane groups of
// the kernel's width W with the last point, as the lane loop pads) with lane type H.
template <class H>
inline void split_points(const detail::FieldData& fd, const std::array<double, 3>* p, size_t count, size_t padded,
                         PointAxes& pa) {
  using D = typename H::D;
  constexpr int HW = H::width;
  const int octaves = fd.fractal == Fractal::None ? 1 : fd.octaves;
  const bool cells = fd.kind == Kind::Worley;
  pa.slots = cells ? 5 : 2;
  pa.hashes.resize(size_t(octaves) * 3 * size_t(pa.slots) * PointAxes::kBlock);
  pa.fracs.resize(size_t(octaves) * 3 * PointAxes::kBlock);
  static constexpr uint32_t kPrimes[3] = {hash::kPrimeX, hash::kPrimeY, hash::kPrimeZ};
  for (size_t i = 0; i < padded; ++i)  // by axis once, not per octave
    for (int a = 0; a < 3; ++a) pa.coords[a][i] = p[std::min(i, count - 1)][a];
  for (int o = 0; o < octaves; ++o) {
    const detail::OctaveData& od = fd.oct[o];
    for (int a = 0; a < 3; ++a) {
      uint32_t* h = pa.hashes.data() + (size_t(o) * 3 + size_t(a)) * size_t(pa.slots) * PointAxes::kBlock;
      float* t = pa.fracs.data() + (size_t(o) * 3 + size_t(a)) * PointAxes::kBlock;
      for (size_t i = 0; i < padded; i += HW) {
        D x;
        std::memcpy(&x, pa.coords[a] + i, sizeof(D));
        const D X = x * od.freq;
        if (cells) {
          const CellAxis<H> c = cell_axis<H>(X, od.period[a], od.iperiod[a], kPrimes[a]);
          for (int s = 0; s < 5; ++s) std::memcpy(h + size_t(s) * PointAxes::kBlock + i, &c.h[s], sizeof(c.h[s]));
          std::memcpy(t + i, &c.t, sizeof(c.t));
        } else {
          const Axis<H> c = split<H>(X, od.period[a], od.iperiod[a], kPrimes[a]);
          std::memcpy(h + i, &c.h0, sizeof(c.h0));
          std::memcpy(h + PointAxes::kBlock + i, &c.h1, sizeof(c.h1));
          std::memcpy(t + i, &c.t, sizeof(c.t));
        }
      }
    }
  }
}

// One lane group of points [i, i + W) of a split block: the octave's noise of kind K.
template <class B, Kind K>
NIMBUS_INLINE typename B::F octave_from_axes(const detail::FieldData& fd, const detail::OctaveData& o,
                                             const PointAxes& pa, int oi, size_t i) {
  using F = typename B::F;
  using U = typename B::U;
  if constexpr (K == Kind::Worley) {
    CellAxis<B> a[3];
    for (int ax = 0; ax < 3; ++ax) {
      for (int s = 0; s < 5; ++s) a[ax].h[s] = load_lanes<U>(pa.hash(oi, ax, s) + i);
      a[ax].t = load_lanes<F>(pa.frac(oi, ax) + i);
    }
    return worley3_cells<B>(a, o.seed, fd.animated, o.cell_time);
  } else {
    Axis<B> a[4];
    for (int ax = 0; ax < 3; ++ax)
      a[ax] = {load_lanes<U>(pa.hash(oi, ax, 0) + i), load_lanes<U>(pa.hash(oi, ax, 1) + i),
               load_lanes<F>(pa.frac(oi, ax) + i)};
    if (fd.animated) {
      a[3] = split_any<B>(o.time, 0.0, 0, hash::kPrimeW);
      if (o.time == std::floor(o.time))  // the second time slice has weight 0 (value4_integer_time)
        return K == Kind::Value ? value4_integer_time<B>(a, o.seed, o.time_norm) : gradient4_integer_time<B>(a, o.seed);
      return K == Kind::Value ? value4<B>(a, o.seed, o.time_norm) : gradient4<B>(a, o.seed);
    }
    return K == Kind::Value ? value3<B>(a, o.seed) : gradient3<B>(a, o.seed);
  }
}

}  // namespace kernels
}  // inline namespace
}  // namespace nimbus::noise
