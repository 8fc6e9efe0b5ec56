// The noise kernels, written once over lane types (simd.hpp) and instantiated per
// instruction set and for the scalar path. Each reads like its formula:
//   value noise     sum over corners of  w(t) * v_corner          (quintic weights)
//   gradient noise  sum over corners of  w(t) * (g_corner . d)    (Perlin 2002)
//   wavelet noise   sum over 27 taps of  B2(x) B2(y) B2(z) * r    (Cook & DeRose 2005)
//   Worley noise    1 - min over nearby cells of |p_cell - x|      (Worley 1996)
#pragma once
#include <algorithm>
#include <cmath>
#include <cstring>

#include "hash.hpp"
#include "nimbus/noise/detail/field_data.hpp"
#include "nimbus/noise/gradient_bound.hpp"
#include "simd.hpp"

namespace nimbus::noise::detail {
// Projected wavelet noise at one point (scalar, in field.cpp; SIMD lanes call it one by one).
float wavelet_projected(const FieldData& fd, const OctaveData& o, double x, double y, double z);
}  // namespace nimbus::noise::detail

namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace kernels {

using namespace simd;

// Exact integer arithmetic on doubles without libm: adding 1.5 * 2^52 rounds a double with
// |x| < 2^51 to an integer, and the low 32 bits of the sum's mantissa are that integer
// modulo 2^32 (two's complement). Inputs are therefore limited to |x| < 2^51 lattice units.
inline constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52

template <class D>
NIMBUS_INLINE D floor_exact(D x) {
  const D r = (x + kMagic) - kMagic;  // nearest integer
  return select(r > x, r - 1.0, r);
}

// Low 32 bits of an integer-valued double (|c| < 2^51).
template <class B>
NIMBUS_INLINE typename B::U low_bits(typename B::D c) {
  using L = std::conditional_t<B::width == 1, int64_t, typename B::L>;
  return low32<typename B::U>(bitcast<L>(c + kMagic));
}

// c mod p for integer-valued c, p in [1, 2^31): floor(c / p) from a reciprocal, then corrected.
template <class D>
NIMBUS_INLINE D mod_exact(D c, double p, double inv_p) {
  D m = c - p * floor_exact(c * inv_p);
  m = select(m < 0.0, m + p, m);
  return select(m >= p, m - p, m);
}

// Lattice coordinate on one axis: hashed coordinates of the two corners and the fraction.
template <class B>
struct Axis {
  typename B::U h0, h1;
  typename B::F t;
};

// Splits x (lattice units) into its cell, wrapped to 32 bits or to the period, and its
// fraction in [0, 1]. All double operations here are exact.
template <class B>
NIMBUS_INLINE Axis<B> split(typename B::D x, double period, int32_t iperiod, uint32_t prime) {
  using D = typename B::D;
  using F = typename B::F;
  using U = typename B::U;
  const D c = floor_exact(x);
  Axis<B> a;
  a.t = convert<F>(x - c);
  U u0, u1;
  if (period > 0.0) {
    u0 = low_bits<B>(mod_exact(c, period, 1.0 / period));
    const U n1 = u0 + 1u;
    u1 = select(n1 == splat<U>(uint32_t(iperiod)), splat<U>(0u), n1);
  } else {
    u0 = low_bits<B>(c);
    u1 = u0 + 1u;
  }
  a.h0 = u0 * prime;
  a.h1 = u1 * prime;
  return a;
}

// Split of a coordinate that is either per lane (B::D) or the same for every lane (double,
// e.g. y and z along a grid row, or time): the latter is split once and broadcast, with the
// same bits as splitting it in every lane.
template <class B, class X>
NIMBUS_INLINE Axis<B> split_any(X x, double period, int32_t iperiod, uint32_t prime) {
  if constexpr (B::width > 1 && std::is_same_v<X, double>) {
    using B1 = Batch<1>;
    const Axis<B1> a = split<B1>(x, period, iperiod, prime);
    return {splat<typename B::U>(a.h0), splat<typename B::U>(a.h1), splat<typename B::F>(a.t)};
  } else {
    return split<B>(x, period, iperiod, prime);
  }
}

template <class F>
NIMBUS_INLINE F fade(F t) {  // 6t^5 - 15t^4 + 10t^3
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

template <class F>
NIMBUS_INLINE F lerp(F s, F a, F b) {
  return a + s * (b - a);
}

// Lattice value in (-1, 1), symmetric about 0, from the top 24 bits of the hash.
template <class B>
NIMBUS_INLINE typename B::F lattice_value(typename B::U h) {
  using F = typename B::F;
  return (convert<F>(bitcast<typename B::I>(h >> 8)) + 0.5f) * (1.0f / 8388608.0f) - 1.0f;
}

// g . (x, y, z) for the 12 cube-edge gradients (+-1, +-1, 0), (+-1, 0, +-1), (0, +-1, +-1).
template <class B>
NIMBUS_INLINE typename B::F edge_dot3(typename B::U idx, typename B::F x, typename B::F y,
                                      typename B::F z) {
  using F = typename B::F;
  using U = typename B::U;
  const U pair = idx >> 2;  // 0: xy, 1: xz, 2: yz
  F u = select(pair == 2u, y, x);
  F v = select(pair == 0u, y, z);
  u = bitcast<F>(bitcast<U>(u) ^ ((idx & 1u) << 31));
  v = bitcast<F>(bitcast<U>(v) ^ ((idx & 2u) << 30));
  return u + v;
}

// Uniform index in [0, 12) from a hash (bias below 2^-22).
template <class U>
NIMBUS_INLINE U edge_index3(U h) {
  return ((h >> 8) * 12u) >> 24;
}
// g . (x, y, z, w) for the 32 tesseract-edge gradients: one component 0, three +-1.
template <class B>
NIMBUS_INLINE typename B::F edge_dot4(typename B::U idx, typename B::F x, typename B::F y,
                                      typename B::F z, typename B::F w) {
  using F = typename B::F;
  using U = typename B::U;
  const U zero_axis = idx >> 3;
  F p = select(zero_axis == 0u, y, x);
  F q = select(zero_axis <= 1u, z, y);
  F r = select(zero_axis <= 2u, w, z);
  p = bitcast<F>(bitcast<U>(p) ^ ((idx & 1u) << 31));
  q = bitcast<F>(bitcast<U>(q) ^ ((idx & 2u) << 30));
  r = bitcast<F>(bitcast<U>(r) ^ ((idx & 4u) << 29));
  return p + q + r;
}

// Trilinear blend of 8 corner values (corner k has offsets k&1, k>>1&1, k>>2&1), x first.
template <class F>
NIMBUS_INLINE F blend8(const F* v, F sx, F sy, F sz) {
  const F x00 = lerp(sx, v[0], v[1]);
  const F x10 = lerp(sx, v[2], v[3]);
  const F x01 = lerp(sx, v[4], v[5]);
  const F x11 = lerp(sx, v[6], v[7]);
  return lerp(sz, lerp(sy, x00, x10), lerp(sy, x01, x11));
}

template <class B>
NIMBUS_INLINE typename B::U corner_hash(const Axis<B>* a, int k, uint32_t seed) {
  using U = typename B::U;
  U h = ((k & 1) ? a[0].h1 : a[0].h0) ^ ((k & 2) ? a[1].h1 : a[1].h0) ^
        ((k & 4) ? a[2].h1 : a[2].h0);
  return hash::mix<U>(h ^ seed);
}

// Value noise from the hashes of the 8 corners (corner_hash order) and the fractions.
template <class B>
NIMBUS_INLINE typename B::F value3_cell(const typename B::U* h, typename B::F tx, typename B::F ty,
                                        typename B::F tz) {
  using F = typename B::F;
  F v[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) v[k] = lattice_value<B>(h[k]);
  return blend8(v, fade(tx), fade(ty), fade(tz));
}

template <class B>
NIMBUS_INLINE typename B::F value3(const Axis<B>* a, uint32_t seed) {
  typename B::U h[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) h[k] = corner_hash<B>(a, k, seed);
  return value3_cell<B>(h, a[0].t, a[1].t, a[2].t);
}

// Perlin's improved noise for given gradient indices at the 8 corners (raw, unscaled), with
// the fractions' fades given (a grid row computes those of y and z once). TY, TZ: a lane type,
// or float for a value shared by every lane.
template <class B, class TY, class TZ>
NIMBUS_INLINE typename B::F gradient3_faded(const typename B::U* idx, typename B::F tx, TY ty, TZ tz,
                                            typename B::F sx, TY sy, TZ sz) {
  using F = typename B::F;
  const F dy[2] = {splat<F>(ty), splat<F>(ty - 1.0f)};
  const F dz[2] = {splat<F>(tz), splat<F>(tz - 1.0f)};
  const F dx[2] = {tx, tx - 1.0f};
  F g[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) g[k] = edge_dot3<B>(idx[k], dx[k & 1], dy[(k >> 1) & 1], dz[k >> 2]);
  return blend8(g, sx, splat<F>(sy), splat<F>(sz));
}

template <class B>
NIMBUS_INLINE typename B::F gradient3_cell(const typename B::U* idx, typename B::F tx,
                                           typename B::F ty, typename B::F tz) {
  return gradient3_faded<B>(idx, tx, ty, tz, fade(tx), fade(ty), fade(tz));
}

template <class B>
NIMBUS_INLINE typename B::F gradient3(const Axis<B>* a, uint32_t seed) {
  using U = typename B::U;
  U idx[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) idx[k] = edge_index3(corner_hash<B>(a, k, seed));
  return gradient3_cell<B>(idx, a[0].t, a[1].t, a[2].t) * kGradientScale3;
}

template <class B>
NIMBUS_INLINE typename B::U corner_hash4(const Axis<B>* a, int k, uint32_t seed) {
  using U = typename B::U;
  U h = ((k & 1) ? a[0].h1 : a[0].h0) ^ ((k & 2) ? a[1].h1 : a[1].h0) ^
        ((k & 4) ? a[2].h1 : a[2].h0) ^ ((k & 8) ? a[3].h1 : a[3].h0);
  return hash::mix<U>(h ^ seed);
}

// Animated value noise: the two 3D value noises at the neighbouring integer times, blended
// by the fade s of the time fraction and divided by sqrt((1-s)^2 + s^2) so the variance is
// the same at every time (time_norm also holds the 1/sqrt(2) that keeps |n| <= 1).
template <class B>
NIMBUS_INLINE typename B::F value4_cell(const typename B::U* h, typename B::F tx, typename B::F ty,
                                        typename B::F tz, typename B::F tw, float time_norm) {
  using F = typename B::F;
  F v[16];
#pragma GCC unroll 16
  for (int k = 0; k < 16; ++k) v[k] = lattice_value<B>(h[k]);
  const F sx = fade(tx), sy = fade(ty), sz = fade(tz);
  return lerp(fade(tw), blend8(v, sx, sy, sz), blend8(v + 8, sx, sy, sz)) * time_norm;
}

template <class B>
NIMBUS_INLINE typename B::F value4(const Axis<B>* a, uint32_t seed, float time_norm) {
  typename B::U h[16];
#pragma GCC unroll 16
  for (int k = 0; k < 16; ++k) h[k] = corner_hash4<B>(a, k, seed);
  return value4_cell<B>(h, a[0].t, a[1].t, a[2].t, a[3].t, time_norm);
}

template <class B>
NIMBUS_INLINE typename B::F gradient4_cell(const typename B::U* idx, typename B::F tx,
                                           typename B::F ty, typename B::F tz,
                                           typename B::F tw) {
  using F = typename B::F;
  F g[16];
#pragma GCC unroll 16
  for (int k = 0; k < 16; ++k) {
    const F dx = (k & 1) ? tx - 1.0f : tx;
    const F dy = (k & 2) ? ty - 1.0f : ty;
    const F dz = (k & 4) ? tz - 1.0f : tz;
    const F dw = (k & 8) ? tw - 1.0f : tw;
    g[k] = edge_dot4<B>(idx[k], dx, dy, dz, dw);
  }
  const F sx = fade(tx), sy = fade(ty), sz = fade(tz);
  return lerp(fade(tw), blend8(g, sx, sy, sz), blend8(g + 8, sx, sy, sz));
}

template <class B>
NIMBUS_INLINE typename B::F gradient4(const Axis<B>* a, uint32_t seed) {
  using U = typename B::U;
  U idx[16];
#pragma GCC unroll 16
  for (int k = 0; k < 16; ++k) idx[k] = corner_hash4<B>(a, k, seed) >> 27;
  return gradient4_cell<B>(idx, a[0].t, a[1].t, a[2].t, a[3].t) * kGradientScale4;
}

// At an integer time the second time slice has weight fade(0) = 0, and lerp(0, a, b) = a + 0 (b - a)
// is a itself wherever a != 0: only the first slice's 8 corners are needed. Lane groups where
// some a is +-0 take the full blend, which decides the sign of that zero. Same bits either way.
template <class B>
NIMBUS_INLINE typename B::F value4_integer_time(const Axis<B>* a, uint32_t seed, float time_norm) {
  using F = typename B::F;
  F v[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) v[k] = lattice_value<B>(corner_hash4<B>(a, k, seed));
  const F first = blend8(v, fade(a[0].t), fade(a[1].t), fade(a[2].t));
  if (simd::any(first == 0.0f)) return value4<B>(a, seed, time_norm);
  return first * time_norm;
}

template <class B>
NIMBUS_INLINE typename B::F gradient4_integer_time(const Axis<B>* a, uint32_t seed) {
  using F = typename B::F;
  const F tx = a[0].t, ty = a[1].t, tz = a[2].t, tw = a[3].t;
  F g[8];
#pragma GCC unroll 16
  for (int k = 0; k < 8; ++k) {
    const F dx = (k & 1) ? tx - 1.0f : tx;
    const F dy = (k & 2) ? ty - 1.0f : ty;
    const F dz = (k & 4) ? tz - 1.0f : tz;
    g[k] = edge_dot4<B>(corner_hash4<B>(a, k, seed) >> 27, dx, dy, dz, tw);
  }
  const F first = blend8(g, fade(tx), fade(ty), fade(tz));
  if (simd::any(first == 0.0f)) return gradient4<B>(a, seed);
  return first * kGradientScale4;
}

// ---- Wavelet noise -------------------------------------------------------------------

// Quadratic B-spline taps around the nearest tile node: indices (wrapped to the tile) of
// nodes c-1, c, c+1 and their weights for t = x - c in [-0.5, 0.5].
template <class B>
struct Taps {
  typename B::I i[3];
  typename B::F w[3];
};

template <class B>
NIMBUS_INLINE Taps<B> bspline_taps(typename B::D x, int32_t n) {
  using D = typename B::D;
  using F = typename B::F;
  using I = typename B::I;
  const D c = floor_exact(x + 0.5);
  const F t = convert<F>(x - c);
  Taps<B> k;
  k.i[1] = bitcast<I>(low_bits<B>(mod_exact(c, double(n), 1.0 / double(n))));
  k.i[0] = select(k.i[1] == splat<I>(0), splat<I>(n - 1), k.i[1] - 1);
  k.i[2] = select(k.i[1] == splat<I>(n - 1), splat<I>(0), k.i[1] + 1);
  const F a = 0.5f - t, b = 0.5f + t;
  k.w[0] = a * a * 0.5f;
  k.w[1] = 0.75f - t * t;
  k.w[2] = b * b * 0.5f;
  return k;
}

template <class B, class X>
NIMBUS_INLINE Taps<B> bspline_taps_any(X x, int32_t n) {
  if constexpr (B::width > 1 && std::is_same_v<X, double>) {
    const Taps<Batch<1>> a = bspline_taps<Batch<1>>(x, n);
    Taps<B> k;
    for (int j = 0; j < 3; ++j) {
      k.i[j] = splat<typename B::I>(a.i[j]);
      k.w[j] = splat<typename B::F>(a.w[j]);
    }
    return k;
  } else {
    return bspline_taps<B>(x, n);
  }
}

template <class I>
NIMBUS_INLINE I wrap_add(I i, int32_t off, int32_t n) {
  const I s = i + off;
  return select(s >= splat<I>(n), s - n, s);
}

// sum_x wx * (sum_y wy * (sum_z wz * r[z][y][x])), the order every path uses.
template <class B>
NIMBUS_INLINE typename B::F wavelet3_slice(const float* tile, int32_t n, const Taps<B>* t,
                                           const int32_t* off) {
  using F = typename B::F;
  using I = typename B::I;
  I ix[3], iy[3], iz[3];
  for (int k = 0; k < 3; ++k) {
    ix[k] = wrap_add(t[0].i[k], off[0], n);
    iy[k] = wrap_add(t[1].i[k], off[1], n) * n;
    iz[k] = wrap_add(t[2].i[k], off[2], n) * (n * n);
  }
  F sx = splat<F>(0.0f);
  for (int a = 0; a < 3; ++a) {
    F sy = splat<F>(0.0f);
    for (int b = 0; b < 3; ++b) {
      const I row = ix[a] + iy[b];
      F sz = t[2].w[0] * gather<F>(tile, row + iz[0]);
      sz = sz + t[2].w[1] * gather<F>(tile, row + iz[1]);
      sz = sz + t[2].w[2] * gather<F>(tile, row + iz[2]);
      sy = sy + t[1].w[b] * sz;
    }
    sx = sx + t[0].w[a] * sy;
  }
  return sx;
}

template <class B, class DY, class DZ>
NIMBUS_INLINE typename B::F wavelet3(const detail::FieldData& fd, const detail::OctaveData& o,
                                     typename B::D x, DY y, DZ z) {
  using F = typename B::F;
  Taps<B> t[3] = {bspline_taps<B>(x, fd.tile_n), bspline_taps_any<B>(y, fd.tile_n),
                  bspline_taps_any<B>(z, fd.tile_n)};
  F r = wavelet3_slice<B>(fd.tile, fd.tile_n, t, o.slice_offset[0]);
  if (o.slices == 1) return r;
  r = r * o.slice_weight[0];
  for (int s = 1; s < o.slices; ++s)
    r = r + o.slice_weight[s] * wavelet3_slice<B>(fd.tile, fd.tile_n, t, o.slice_offset[s]);
  return r;
}


}  // namespace kernels
}  // inline namespace
}  // namespace nimbus::noise

#include "worley_kernel.hpp"  // Worley noise, built on the lattice helpers above

namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace kernels {

// ---- One sample of the whole field -----------------------------------------------------

// One octave at x (per lane) and y, z (per lane, or shared by all lanes as doubles).
// K: the field's kind, fixed at compile time where the caller knows it (each kind's loop is then
// compiled on its own, without the others' registers), or Kind(-1) to read fd.kind.
inline constexpr Kind kAnyKind = static_cast<Kind>(-1);

template <class B, Kind K = kAnyKind, class DY, class DZ>
NIMBUS_INLINE typename B::F octave_noise(const detail::FieldData& fd, const detail::OctaveData& o,
                                         typename B::D x, DY y, DZ z) {
  if constexpr (K == kAnyKind) {
    switch (fd.kind) {
      case Kind::Value: return octave_noise<B, Kind::Value>(fd, o, x, y, z);
      case Kind::Gradient: return octave_noise<B, Kind::Gradient>(fd, o, x, y, z);
      case Kind::Wavelet: return octave_noise<B, Kind::Wavelet>(fd, o, x, y, z);
      case Kind::Worley: return octave_noise<B, Kind::Worley>(fd, o, x, y, z);
    }
  }
  using F = typename B::F;
  using D = typename B::D;
  const D X = x * o.freq;
  const DY Y = y * o.freq;
  const DZ Z = z * o.freq;
  if constexpr (K == Kind::Wavelet) {
    if (fd.projected) {
      F r;
      if constexpr (B::width == 1) {
        r = detail::wavelet_projected(fd, o, X, Y, Z);
      } else {
        for (int l = 0; l < B::width; ++l)
          r[l] = detail::wavelet_projected(fd, o, X[l], lane(Y, l), lane(Z, l));
      }
      return r;
    }
    return wavelet3<B>(fd, o, X, Y, Z);
  }
  if constexpr (K == Kind::Worley) return worley3<B>(o, fd.animated, X, Y, Z);
  Axis<B> a[4] = {split<B>(X, o.period[0], o.iperiod[0], hash::kPrimeX),
                  split_any<B>(Y, o.period[1], o.iperiod[1], hash::kPrimeY),
                  split_any<B>(Z, o.period[2], o.iperiod[2], hash::kPrimeZ),
                  {}};
  if (fd.animated) {
    a[3] = split_any<B>(o.time, 0.0, 0, hash::kPrimeW);
    // The full blend at every time: NoiseField::eval, the reference that the batch paths'
    // integer-time shortcut (point_axes.hpp) is tested against.
    return K == Kind::Value ? value4<B>(a, o.seed, o.time_norm) : gradient4<B>(a, o.seed);
  }
  return K == Kind::Value ? value3<B>(a, o.seed) : gradient3<B>(a, o.seed);
}

// The fractal sum over octaves; octave(o, i) evaluates one octave.
template <class B, class OctaveFn>
NIMBUS_INLINE typename B::F fractal_sum(const detail::FieldData& fd, OctaveFn&& octave) {
  using F = typename B::F;
  if (fd.fractal == Fractal::None) return octave(fd.oct[0], 0);
  F acc = splat<F>(0.0f);
  for (int i = 0; i < fd.octaves; ++i) {
    const detail::OctaveData& o = fd.oct[i];
    const F n = octave(o, i);
    switch (fd.fractal) {
      case Fractal::Fbm: acc = acc + o.amp * n; break;
      case Fractal::Turbulence: acc = acc + o.amp * simd::abs(n); break;
      case Fractal::Ridged: {
        const F r = 1.0f - simd::abs(n);
        acc = acc + o.amp * (r * r);
        break;
      }
      case Fractal::None: break;
    }
  }
  return acc * fd.inv_amp_sum;
}

template <class B, Kind K = kAnyKind, class DY, class DZ>
NIMBUS_INLINE typename B::F field(const detail::FieldData& fd, typename B::D x, DY y, DZ z) {
  return fractal_sum<B>(fd, [&](const detail::OctaveData& o, int) NIMBUS_INLINE_LAMBDA {
    return octave_noise<B, K>(fd, o, x, y, z);
  });
}

// ---- Grid rows: what y, z and time fix for a whole row, computed once ------------------

// Per octave: the split y, z and time axes (value, gradient), or for wavelet noise the
// column sums S_s[c] = sum_b wy_b (sum_k wz_k r[z_k][y_b][c]) of each time slice s, in the
// order wavelet3_slice adds them, so a sample needs 3 taps instead of 27 and the same bits.
struct RowOctave {
  Axis<Batch<1>> y, z, w;
  // Value, gradient: the y, z (and w) part of each corner's hash before mixing, with the seed:
  // corner k hashes mix(hx[k & 1] ^ yzw[k >> 1]), the same bits as corner_hash(4).
  uint32_t yzw[8];
  float fy = 0.0f, fz = 0.0f;  // value, gradient: fade of the y and z fractions
  // Gradient: for each y, z corner combination j (bit 0: y + 1, bit 1: z + 1) and gradient
  // index g < 12, the second term v of edge_dot3, which only y and z give: +-dy for the xy
  // gradients, +-dz for the others (sign: g & 2). Padded to 16 entries.
  alignas(64) float vterm[4][16];
  CellAxis<Batch<1>> cy, cz;  // Worley: the row's y and z cell axes
  const float* wcells = nullptr;  // Worley: the row's cell table (row_axis.hpp), or none
  const uint32_t* lcells = nullptr;  // value, gradient: the row's lattice table, or none
  int64_t lstride = 0;               // its entries per corner combination
  float* cols[3];
};

struct RowContext {
  double y = 0.0, z = 0.0;
  RowOctave oct[kMaxOctaves];
};

// Column sums of one time slice (tile offset `off`) for the unwrapped columns [c_lo, c_hi],
// or for all n columns when that range covers the tile.
template <class B>
inline void wavelet_columns(const detail::FieldData& fd, double Y, double Z, const int32_t* off,
                            int64_t c_lo, int64_t c_hi, float* out) {
  using B1 = Batch<1>;
  using F = typename B::F;
  constexpr int W = B::width;
  const int32_t n = fd.tile_n;
  const Taps<B1> ty = bspline_taps<B1>(Y, n), tz = bspline_taps<B1>(Z, n);
  const float* rows[3][3];
  for (int b = 0; b < 3; ++b)
    for (int k = 0; k < 3; ++k)
      rows[b][k] = fd.tile + size_t(wrap_add(tz.i[k], off[2], n)) * n * n +
                   size_t(wrap_add(ty.i[b], off[1], n)) * n;
  int64_t left = std::min<int64_t>(c_hi - c_lo + 1, n);
  int64_t c = left == n ? 0 : ((c_lo % n) + n) % n;
  while (left > 0) {  // the wrapped range, in contiguous pieces
    const int64_t piece = std::min<int64_t>(left, n - c);
    int64_t j = 0;
    for (; j + W <= piece; j += W) {
      F sy = splat<F>(0.0f);
      for (int b = 0; b < 3; ++b) {
        F r0, r1, r2;
        std::memcpy(&r0, rows[b][0] + c + j, sizeof(F));
        std::memcpy(&r1, rows[b][1] + c + j, sizeof(F));
        std::memcpy(&r2, rows[b][2] + c + j, sizeof(F));
        F sz = tz.w[0] * r0;
        sz = sz + tz.w[1] * r1;
        sz = sz + tz.w[2] * r2;
        sy = sy + ty.w[b] * sz;
      }
      std::memcpy(out + c + j, &sy, sizeof(F));
    }
    for (; j < piece; ++j) {
      float sy = 0.0f;
      for (int b = 0; b < 3; ++b) {
        float sz = tz.w[0] * rows[b][0][c + j];
        sz = sz + tz.w[1] * rows[b][1][c + j];
        sz = sz + tz.w[2] * rows[b][2][c + j];
        sy = sy + ty.w[b] * sz;
      }
      out[c + j] = sy;
    }
    left -= piece;
    c = 0;
  }
}

// Prepares row (y, z) for samples whose x lies in [x_lo, x_hi]. `scratch` holds
// kMaxOctaves * 3 * tile_n floats (wavelet noise only).
template <class B>
inline void prepare_row(const detail::FieldData& fd, double y, double z, double x_lo,
                        double x_hi, RowContext& rc, float* scratch) {
  using B1 = Batch<1>;
  rc.y = y;
  rc.z = z;
  const int octaves = fd.fractal == Fractal::None ? 1 : fd.octaves;
  for (int i = 0; i < octaves; ++i) {
    const detail::OctaveData& o = fd.oct[i];
    RowOctave& r = rc.oct[i];
    const double Y = y * o.freq, Z = z * o.freq;
    if (fd.kind == Kind::Worley) {
      r.cy = cell_axis<B1>(Y, o.period[1], o.iperiod[1], hash::kPrimeY);
      r.cz = cell_axis<B1>(Z, o.period[2], o.iperiod[2], hash::kPrimeZ);
    } else if (fd.kind != Kind::Wavelet) {
      r.y = split<B1>(Y, o.period[1], o.iperiod[1], hash::kPrimeY);
      r.z = split<B1>(Z, o.period[2], o.iperiod[2], hash::kPrimeZ);
      if (fd.animated) r.w = split<B1>(o.time, 0.0, 0, hash::kPrimeW);
      r.fy = fade(r.y.t);
      r.fz = fade(r.z.t);
      for (int j = 0; j < 4; ++j) {
        const float dy = (j & 1) ? r.y.t - 1.0f : r.y.t, dz = (j & 2) ? r.z.t - 1.0f : r.z.t;
        for (uint32_t g = 0; g < 16; ++g) {
          const float v = (g >> 2) == 0 ? dy : dz;
          r.vterm[j][g] = g < 12 ? bitcast<float>(bitcast<uint32_t>(v) ^ ((g & 2u) << 30)) : 0.0f;
        }
      }
      for (int j = 0; j < 8; ++j)
        r.yzw[j] = ((j & 1) ? r.y.h1 : r.y.h0) ^ ((j & 2) ? r.z.h1 : r.z.h0) ^
                   (fd.animated ? ((j & 4) ? r.w.h1 : r.w.h0) : 0u) ^ o.seed;
    } else if (!fd.projected) {
      // The taps reach one node either side of the nodes nearest to the row's ends.
      const int64_t lo = static_cast<int64_t>(std::floor(x_lo * o.freq + 0.5)) - 1;
      const int64_t hi = static_cast<int64_t>(std::floor(x_hi * o.freq + 0.5)) + 1;
      for (int s = 0; s < o.slices; ++s) {
        r.cols[s] = scratch + (size_t(i) * 3 + s) * fd.tile_n;
        const int32_t* off = o.slice_offset[s];
        wavelet_columns<B>(fd, Y, Z, off, lo + off[0], hi + off[0], r.cols[s]);
      }
    }
  }
}

// One sample group of a grid row, with the row's context. K is fd.kind, fixed at compile time
// so that each kind's row loop is compiled on its own (a loop holding all three kinds spills
// registers).
template <class B, Kind K>
NIMBUS_INLINE typename B::F field_row(const detail::FieldData& fd, typename B::D x,
                                      const RowContext& rc) {
  using F = typename B::F;
  using I = typename B::I;
  return fractal_sum<B>(fd, [&](const detail::OctaveData& o, int i) NIMBUS_INLINE_LAMBDA -> F {
    if constexpr (K == Kind::Worley) {
      return worley3<B>(o, fd.animated, x * o.freq, rc.y * o.freq, rc.z * o.freq);
    } else if constexpr (K != Kind::Wavelet) {
      using U = typename B::U;
      const RowOctave& r = rc.oct[i];
      Axis<B> a[4];
      a[0] = split<B>(x * o.freq, o.period[0], o.iperiod[0], hash::kPrimeX);
      a[1] = {splat<U>(r.y.h0), splat<U>(r.y.h1), splat<F>(r.y.t)};
      a[2] = {splat<U>(r.z.h0), splat<U>(r.z.h1), splat<F>(r.z.t)};
      if (fd.animated) {
        a[3] = {splat<U>(r.w.h0), splat<U>(r.w.h1), splat<F>(r.w.t)};
        return K == Kind::Value ? value4<B>(a, o.seed, o.time_norm) : gradient4<B>(a, o.seed);
      }
      return K == Kind::Value ? value3<B>(a, o.seed) : gradient3<B>(a, o.seed);
    } else {
      if (fd.projected) return octave_noise<B>(fd, o, x, rc.y, rc.z);
      const Taps<B> tx = bspline_taps<B>(x * o.freq, fd.tile_n);
      F r = splat<F>(0.0f);
      for (int s = 0; s < o.slices; ++s) {
        const float* cols = rc.oct[i].cols[s];
        F sx = splat<F>(0.0f);
        for (int a = 0; a < 3; ++a) {
          const I ix = wrap_add(tx.i[a], o.slice_offset[s][0], fd.tile_n);
          sx = sx + tx.w[a] * gather<F>(cols, ix);
        }
        if (o.slices == 1) return sx;
        r = s == 0 ? sx * o.slice_weight[0] : r + o.slice_weight[s] * sx;
      }
      return r;
    }
  });
}

// Lanes from memory (p: W consecutive elements).
template <class T>
NIMBUS_INLINE T load_lanes(const std::remove_reference_t<decltype(lane(T{}, 0))>* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

}  // namespace kernels
}  // inline namespace
}  // namespace nimbus::noise
