// Lane types for noise kernels written once and compiled per instruction set.
// Batch<W> holds GCC vector types of W lanes; Batch<1> holds plain scalars, so the same
// kernel source is the scalar path. Every operation used here is exact IEEE arithmetic or
// integer arithmetic, lane by lane, so all widths give identical bits (-ffp-contract=off).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#if defined(__SSE4_1__) || defined(__AVX2__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

#ifndef NIMBUS_KERNEL_NS
#define NIMBUS_KERNEL_NS base
#endif

// Each instruction-set level compiles these inline functions into its own namespace, so the
// linker can never hand one level's copy to another.
namespace nimbus::noise {
inline namespace NIMBUS_KERNEL_NS {
namespace simd {

template <int W>
struct Batch {
  static constexpr int width = W;
  typedef float F __attribute__((vector_size(4 * W)));
  typedef int32_t I __attribute__((vector_size(4 * W)));
  typedef uint32_t U __attribute__((vector_size(4 * W)));
  typedef double D __attribute__((vector_size(8 * W)));
  typedef int64_t L __attribute__((vector_size(8 * W)));
};

template <>
struct Batch<1> {
  static constexpr int width = 1;
  using F = float;
  using I = int32_t;
  using U = uint32_t;
  using D = double;
  using L = bool;
};

#define NIMBUS_INLINE inline __attribute__((always_inline))
// Lambdas passed to kernels must inline too: a call would pass wide vectors through memory.
#define NIMBUS_INLINE_LAMBDA __attribute__((always_inline))

template <class T>
NIMBUS_INLINE T splat(auto s) {
  if constexpr (std::is_same_v<decltype(s), T>) {  // already lanes (or the scalar path's scalar)
    return s;
  } else if constexpr (std::is_arithmetic_v<T>) {
    return static_cast<T>(s);
  } else {
    using E = std::remove_reference_t<decltype(T{}[0])>;
    return T{} + static_cast<E>(s);
  }
}

// Lane-wise a ? b : c. The mask is a comparison result (bool, or an integer vector of -1/0).
template <class M, class T>
NIMBUS_INLINE T select(M m, T a, T b) {
  if constexpr (std::is_arithmetic_v<T>) {
    // Branch-free for scalars too: the conditions in noise kernels are random (gradient
    // indices, cell parities), so a branch would be mispredicted half the time.
    using Bits = std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>;
    const Bits mask = Bits(0) - static_cast<Bits>(static_cast<bool>(m));
    Bits ab, bb;
    std::memcpy(&ab, &a, sizeof(T));
    std::memcpy(&bb, &b, sizeof(T));
    const Bits r = (ab & mask) | (bb & ~mask);
    T out;
    std::memcpy(&out, &r, sizeof(T));
    return out;
  } else {
    using IM = decltype(a < b);  // integer vector with the lane size of T
    return (m != IM{}) ? a : b;
  }
}

// Converts lane-wise (value conversion, truncating toward zero for float -> int).
template <class To, class From>
NIMBUS_INLINE To convert(From x) {
  if constexpr (std::is_arithmetic_v<From>) {
    return static_cast<To>(x);
  } else {
    return __builtin_convertvector(x, To);
  }
}

// Same bits, another type.
template <class To, class From>
NIMBUS_INLINE To bitcast(From x) {
  static_assert(sizeof(To) == sizeof(From));
  To r;
  std::memcpy(&r, &x, sizeof(To));
  return r;
}

template <class F>
NIMBUS_INLINE F abs(F x) {
  if constexpr (std::is_arithmetic_v<F>) {
    return std::fabs(x);
  } else {
    using U = decltype(x < x);
    return bitcast<F>(bitcast<U>(x) & 0x7fffffff);
  }
}

// floor of doubles, exactly, using the widest rounding instruction the target has.
template <class D>
NIMBUS_INLINE D floor(D x) {
  if constexpr (std::is_arithmetic_v<D>) {
    return std::floor(x);
  } else {
    constexpr int n = sizeof(D) / sizeof(double);
    D r;
#if defined(__AVX512F__)
    if constexpr (n % 8 == 0) {
      for (int i = 0; i < n; i += 8) {
        __m512d v;
        std::memcpy(&v, reinterpret_cast<const double*>(&x) + i, sizeof v);
        v = _mm512_roundscale_pd(v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        std::memcpy(reinterpret_cast<double*>(&r) + i, &v, sizeof v);
      }
      return r;
    }
#endif
#if defined(__AVX__)
    if constexpr (n % 4 == 0) {
      for (int i = 0; i < n; i += 4) {
        __m256d v;
        std::memcpy(&v, reinterpret_cast<const double*>(&x) + i, sizeof v);
        v = _mm256_floor_pd(v);
        std::memcpy(reinterpret_cast<double*>(&r) + i, &v, sizeof v);
      }
      return r;
    }
#endif
#if defined(__SSE4_1__)
    if constexpr (n % 2 == 0) {
      for (int i = 0; i < n; i += 2) {
        __m128d v;
        std::memcpy(&v, reinterpret_cast<const double*>(&x) + i, sizeof v);
        v = _mm_floor_pd(v);
        std::memcpy(reinterpret_cast<double*>(&r) + i, &v, sizeof v);
      }
      return r;
    }
#endif
    for (int i = 0; i < n; ++i) r[i] = std::floor(x[i]);
    return r;
  }
}

// Low 32 bits of each 64-bit lane (x: W int64 lanes, result: W uint32 lanes).
template <class U, class L>
NIMBUS_INLINE U low32(L x) {
  if constexpr (std::is_arithmetic_v<L>) {
    return static_cast<U>(static_cast<uint64_t>(x));
  } else {
    constexpr int n = sizeof(L) / sizeof(int64_t);
    U r;
#if defined(__AVX512F__)
    if constexpr (n % 8 == 0) {
      for (int i = 0; i < n; i += 8) {
        __m512i v;
        std::memcpy(&v, reinterpret_cast<const int64_t*>(&x) + i, sizeof v);
        const __m256i lo = _mm512_cvtepi64_epi32(v);
        std::memcpy(reinterpret_cast<uint32_t*>(&r) + i, &lo, sizeof lo);
      }
      return r;
    }
#endif
#if defined(__AVX2__)
    if constexpr (n % 4 == 0) {
      const __m256i even = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
      for (int i = 0; i < n; i += 4) {
        __m256i v;
        std::memcpy(&v, reinterpret_cast<const int64_t*>(&x) + i, sizeof v);
        const __m128i lo = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(v, even));
        std::memcpy(reinterpret_cast<uint32_t*>(&r) + i, &lo, sizeof lo);
      }
      return r;
    }
#endif
#if defined(__SSE4_1__)
    if constexpr (n % 4 == 0) {
      for (int i = 0; i < n; i += 4) {
        __m128i a, b;
        std::memcpy(&a, reinterpret_cast<const int64_t*>(&x) + i, sizeof a);
        std::memcpy(&b, reinterpret_cast<const int64_t*>(&x) + i + 2, sizeof b);
        const __m128 lo = _mm_shuffle_ps(_mm_castsi128_ps(a), _mm_castsi128_ps(b), _MM_SHUFFLE(2, 0, 2, 0));
        std::memcpy(reinterpret_cast<uint32_t*>(&r) + i, &lo, sizeof lo);
      }
      return r;
    }
#endif
    for (int i = 0; i < n; ++i) r[i] = static_cast<uint32_t>(static_cast<uint64_t>(x[i]));
    return r;
  }
}

// Loads table[idx[lane]] for each lane.
template <class F, class I>
NIMBUS_INLINE F gather(const float* table, I idx) {
  if constexpr (std::is_arithmetic_v<F>) {
    return table[idx];
  } else {
    constexpr int n = sizeof(F) / sizeof(float);
    F r;
#if defined(__AVX512F__)
    if constexpr (n == 16) {
      __m512i vi;
      std::memcpy(&vi, &idx, sizeof vi);
      __m512 v = _mm512_i32gather_ps(vi, table, 4);
      std::memcpy(&r, &v, sizeof v);
      return r;
    }
#endif
#if defined(__AVX2__)
    if constexpr (n == 8) {
      __m256i vi;
      std::memcpy(&vi, &idx, sizeof vi);
      __m256 v = _mm256_i32gather_ps(table, vi, 4);
      std::memcpy(&r, &v, sizeof v);
      return r;
    }
#endif
    for (int i = 0; i < n; ++i) r[i] = table[idx[i]];
    return r;
  }
}

// Lane-wise minimum (a < b ? a : b; neither argument is ever NaN in the kernels).
template <class F>
NIMBUS_INLINE F min(F a, F b) {
  return select(a < b, a, b);
}

// Lane-wise square root: IEEE sqrt is correctly rounded, so every width gives the same bits.
template <class F>
NIMBUS_INLINE F sqrt(F x) {
  if constexpr (std::is_arithmetic_v<F>) {
    return std::sqrt(x);
  } else {
    constexpr int n = sizeof(F) / sizeof(float);
    F r;
#if defined(__AVX512F__)
    if constexpr (n == 16) {
      __m512 v;
      std::memcpy(&v, &x, sizeof v);
      v = _mm512_sqrt_ps(v);
      std::memcpy(&r, &v, sizeof v);
      return r;
    }
#endif
#if defined(__AVX__)
    if constexpr (n == 8) {
      __m256 v;
      std::memcpy(&v, &x, sizeof v);
      v = _mm256_sqrt_ps(v);
      std::memcpy(&r, &v, sizeof v);
      return r;
    }
#endif
#if defined(__SSE4_1__)
    if constexpr (n == 4) {
      __m128 v;
      std::memcpy(&v, &x, sizeof v);
      v = _mm_sqrt_ps(v);
      std::memcpy(&r, &v, sizeof v);
      return r;
    }
#endif
    for (int i = 0; i < n; ++i) r[i] = std::sqrt(x[i]);
    return r;
  }
}

// floor of floats with |x| < 2^31, exactly: truncate, then step down where that rounded up.
template <class F, class I>
NIMBUS_INLINE F floor_small(F x) {
  const F t = convert<F>(convert<I>(x));
  return select(t > x, t - 1.0f, t);
}

// Whether any lane of a comparison result is true.
template <class M>
NIMBUS_INLINE bool any(M m) {
  if constexpr (std::is_same_v<M, bool>) {
    return m;
  } else {
    constexpr int n = sizeof(M) / sizeof(m[0]);
    static_assert(sizeof(m[0]) == 4, "any() takes 32-bit lane masks");
#if defined(__AVX512F__)
    if constexpr (n == 16) {
      __m512i v;
      std::memcpy(&v, &m, sizeof v);
      return _mm512_test_epi32_mask(v, v) != 0;
    }
#endif
#if defined(__AVX__)
    if constexpr (n == 8) {
      __m256 v;
      std::memcpy(&v, &m, sizeof v);
      return _mm256_movemask_ps(v) != 0;  // the sign bit of each lane of -1 / 0
    }
#endif
#if defined(__SSE4_1__)
    if constexpr (n == 4) {
      __m128 v;
      std::memcpy(&v, &m, sizeof v);
      return _mm_movemask_ps(v) != 0;
    }
#endif
    bool r = false;
    for (int i = 0; i < n; ++i) r |= m[i] != 0;
    return r;
  }
}

template <class T>
NIMBUS_INLINE auto lane(const T& v, int i) {
  if constexpr (std::is_arithmetic_v<T>) {
    (void)i;
    return v;
  } else {
    return v[i];
  }
}

}  // namespace simd
}  // inline namespace
}  // namespace nimbus::noise

