// Wavelet-noise tile construction (see wavelet_tile.hpp for the equations).
#include "nimbus/noise/wavelet_tile.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "hash.hpp"

namespace nimbus::noise {
namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

// Solves the symmetric positive definite system A x = b (dense, small) by Cholesky.
std::vector<double> solve_spd(std::vector<double> a, std::vector<double> b, int m) {
  for (int j = 0; j < m; ++j) {
    double d = a[j * m + j];
    for (int k = 0; k < j; ++k) d -= a[j * m + k] * a[j * m + k];
    d = std::sqrt(d);
    a[j * m + j] = d;
    for (int i = j + 1; i < m; ++i) {
      double s = a[i * m + j];
      for (int k = 0; k < j; ++k) s -= a[i * m + k] * a[j * m + k];
      a[i * m + j] = s / d;
    }
  }
  for (int i = 0; i < m; ++i) {  // L y = b
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= a[i * m + k] * b[k];
    b[i] = s / a[i * m + i];
  }
  for (int i = m - 1; i >= 0; --i) {  // L^T x = y
    double s = b[i];
    for (int k = i + 1; k < m; ++k) s -= a[k * m + i] * b[k];
    b[i] = s / a[i * m + i];
  }
  return b;
}

}  // namespace

AnalysisFilter wavelet_analysis_filter(int n) {
  if (n < 8 || n % 2 != 0) throw std::invalid_argument("wavelet tile size must be even and >= 8");
  const int m = n / 2;
  // U: fine[2k] = 3/4 c_k + 1/4 c_{k+1},  fine[2k+1] = 1/4 c_k + 3/4 c_{k+1}   (n x m)
  std::vector<double> u(size_t(n) * m, 0.0);
  for (int k = 0; k < m; ++k) {
    u[size_t(2 * k) * m + k] += 0.75;
    u[size_t(2 * k) * m + (k + 1) % m] += 0.25;
    u[size_t(2 * k + 1) * m + k] += 0.25;
    u[size_t(2 * k + 1) * m + (k + 1) % m] += 0.75;
  }
  // G: Gram matrix of unit-spaced quadratic B-splines, <B(x - i), B(x - j)> = B5(i - j),
  // the quintic B-spline at integers: (1, 26, 66, 26, 1) / 120.
  const double g[5] = {1.0 / 120, 26.0 / 120, 66.0 / 120, 26.0 / 120, 1.0 / 120};
  std::vector<double> gu(size_t(n) * m, 0.0);  // G U
  for (int i = 0; i < n; ++i)
    for (int d = -2; d <= 2; ++d) {
      const int j = wrap(i + d, n);
      for (int k = 0; k < m; ++k) gu[size_t(i) * m + k] += g[d + 2] * u[size_t(j) * m + k];
    }
  std::vector<double> utgu(size_t(m) * m, 0.0);  // U^T G U
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += u[size_t(i) * m + a] * gu[size_t(i) * m + b];
      utgu[size_t(a) * m + b] = s;
    }
  std::vector<double> e0(m, 0.0);
  e0[0] = 1.0;
  const std::vector<double> q = solve_spd(utgu, e0, m);
  // Row 0 of D = (U^T G U)^-1 U^T G: coarse[0] = sum_j row[j] fine[j].
  std::vector<double> row(n, 0.0);
  for (int j = 0; j < n; ++j) {
    double s = 0.0;
    for (int k = 0; k < m; ++k) s += q[k] * gu[size_t(j) * m + k];
    row[j] = s;
  }
  // Offsets relative to 2m: the filter is symmetric about -1/2.
  const int half = n > 64 ? 32 : n / 2;  // dropped taps (|j| > 32) are below 3e-6
  AnalysisFilter f;
  f.first = -half;
  for (int o = -half; o < half; ++o) f.taps.push_back(static_cast<float>(row[wrap(o, n)]));
  return f;
}

void wavelet_downsample(const float* fine, float* coarse, int n, const AnalysisFilter& f) {
  const int taps = static_cast<int>(f.taps.size());
  for (int k = 0; k < n / 2; ++k) {
    float s = 0.0f;
    int j = wrap(2 * k + f.first, n);
    for (int t = 0; t < taps; ++t) {
      s += f.taps[t] * fine[j];
      if (++j == n) j = 0;
    }
    coarse[k] = s;
  }
}

void wavelet_upsample(const float* coarse, float* fine, int n) {
  const int m = n / 2;
  for (int k = 0; k < m; ++k) {
    const float a = coarse[k], b = coarse[(k + 1) % m];
    fine[2 * k] = 0.75f * a + 0.25f * b;
    fine[2 * k + 1] = 0.25f * a + 0.75f * b;
  }
}

namespace {

typedef float Row8 __attribute__((vector_size(32)));

// out[x] = out[x] + a * in[x] for x < len, in 8-wide chunks then one by one: the same float
// operations, in the same order, for every x whatever the instruction set.
void axpy(float* out, float a, const float* in, int len) {
  int x = 0;
  for (; x + 8 <= len; x += 8) {
    Row8 o, i;
    std::memcpy(&o, out + x, sizeof o);
    std::memcpy(&i, in + x, sizeof i);
    o = o + a * i;
    std::memcpy(out + x, &o, sizeof o);
  }
  for (; x < len; ++x) out[x] = out[x] + a * in[x];
}

}  // namespace

// Rows r = 0..n-1 of `len` floats at base + r * stride hold n lines (one per x position across
// the rows); replaces them by U(D(line)). scratch holds (n / 2) * len floats.
void project_rows(float* base, size_t stride, int n, int len, const AnalysisFilter& f,
                  float* scratch) {
  const int m = n / 2, taps = static_cast<int>(f.taps.size());
  for (int k = 0; k < m; ++k) {  // coarse row k = sum_t taps[t] * row(2k + first + t)
    float* c = scratch + size_t(k) * len;
    std::fill(c, c + len, 0.0f);
    int r = ((2 * k + f.first) % n + n) % n;
    for (int t = 0; t < taps; ++t) {
      axpy(c, f.taps[t], base + size_t(r) * stride, len);
      if (++r == n) r = 0;
    }
  }
  for (int k = 0; k < m; ++k) {  // fine rows 2k, 2k+1 from coarse rows k, k+1
    const float* a = scratch + size_t(k) * len;
    const float* b = scratch + size_t((k + 1) % m) * len;
    float* even = base + size_t(2 * k) * stride;
    float* odd = base + size_t(2 * k + 1) * stride;
    for (int x = 0; x < len; ++x) {
      even[x] = 0.75f * a[x] + 0.25f * b[x];
      odd[x] = 0.25f * a[x] + 0.75f * b[x];
    }
  }
}

WaveletTile::WaveletTile(int n, uint32_t seed) : n_(n), seed_(seed) {
  if (n < 8 || n > 512 || n % 2 != 0)
    throw std::invalid_argument("wavelet tile size " + std::to_string(n) +
                                " must be even and in [8, 512]");
  const size_t count = size_t(n) * n * n;
  std::vector<float> white(count);
  // White noise, uniform with unit variance: only exact operations, so every build agrees.
  tbb::parallel_for(0, n, [&](int z) {
    for (size_t i = size_t(z) * n * n; i < size_t(z + 1) * n * n; ++i) {
      const uint32_t h = hash::mix<uint32_t>(static_cast<uint32_t>(i) * 0x9e3779b1u ^
                                             hash::mix<uint32_t>(seed + 0x632be5abu));
      const float u = (static_cast<float>(h >> 8) + 0.5f) * (1.0f / 16777216.0f);  // (0, 1)
      white[i] = (2.0f * u - 1.0f) * 1.7320508f;
    }
  });

  // Coarse part: D then U along x, then y, then z. Each pass works on whole rows that are
  // contiguous along another axis (the x pass on transposed planes), so every output is the
  // same sequence of float operations as the one-line formula, vectorised across the row.
  std::vector<float> coarse = white;
  const AnalysisFilter filter = wavelet_analysis_filter(n);
  const size_t plane = size_t(n) * n;
  // x: transpose each z plane, project its rows (now indexed by x), transpose back.
  tbb::parallel_for(0, n, [&](int z) {
    std::vector<float> t(plane), scratch(plane / 2);
    float* p = coarse.data() + z * plane;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) t[size_t(x) * n + y] = p[size_t(y) * n + x];
    project_rows(t.data(), size_t(n), n, n, filter, scratch.data());
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) p[size_t(y) * n + x] = t[size_t(x) * n + y];
  });
  // y: rows of a z plane.
  tbb::parallel_for(0, n, [&](int z) {
    std::vector<float> scratch(plane / 2);
    project_rows(coarse.data() + z * plane, size_t(n), n, n, filter, scratch.data());
  });
  // z: for each y, the rows z * n^2 + y * n.
  tbb::parallel_for(0, n, [&](int y) {
    std::vector<float> scratch(plane / 2);
    project_rows(coarse.data() + size_t(y) * n, plane, n, n, filter, scratch.data());
  });
  for (size_t i = 0; i < count; ++i) coarse[i] = white[i] - coarse[i];  // band-pass part

  // Add a copy shifted by an odd offset on every axis (C&D: evens out the variance of
  // even and odd nodes), then normalise.
  int off = n / 2;
  if (off % 2 == 0) ++off;
  data_.resize(count);
  std::vector<double> plane_sum(n, 0.0);
  tbb::parallel_for(0, n, [&](int z) {
    double s2 = 0.0;
    const int zs = (z + off) % n;
    for (int y = 0; y < n; ++y) {
      const int ys = (y + off) % n;
      for (int x = 0; x < n; ++x) {
        const int xs = (x + off) % n;
        const float v = coarse[(size_t(z) * n + y) * n + x] + coarse[(size_t(zs) * n + ys) * n + xs];
        data_[(size_t(z) * n + y) * n + x] = v;
        s2 += double(v) * v;
      }
    }
    plane_sum[z] = s2;
  });
  double total = 0.0;
  for (double s : plane_sum) total += s;
  band_sd_ = std::sqrt(total / double(count));
  scale_ = 1.0 / (kWaveletClampSigmas * band_sd_);
  const float scale = static_cast<float>(scale_);
  int64_t clamped = 0;
  for (float& v : data_) {
    const float w = v * scale;
    v = std::clamp(w, -1.0f, 1.0f);
    clamped += (v != w);
  }
  clamped_ = clamped;
}

std::shared_ptr<const WaveletTile> WaveletTile::shared(int n, uint32_t seed) {
  static std::mutex mutex;
  static std::map<std::pair<int, uint32_t>, std::weak_ptr<const WaveletTile>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{n, seed}];
  if (auto t = slot.lock()) return t;
  auto t = std::make_shared<const WaveletTile>(n, seed);
  slot = t;
  return t;
}

}  // namespace nimbus::noise
