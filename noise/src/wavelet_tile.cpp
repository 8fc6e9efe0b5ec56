// Wavelet-noise tile construction (see wavelet_tile.hpp for the equations).
#include "nimbus/noise/wavelet_tile.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
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

  // Coarse part: D then U along each axis, line by line.
  std::vector<float> coarse = white;
  const AnalysisFilter filter = wavelet_analysis_filter(n);
  const size_t stride[3] = {1, size_t(n), size_t(n) * n};
  for (int axis = 0; axis < 3; ++axis) {
    const size_t s = stride[axis];
    const size_t s1 = stride[(axis + 1) % 3], s2 = stride[(axis + 2) % 3];
    tbb::parallel_for(0, n, [&](int b) {
      std::vector<float> line(n), half(n / 2);
      for (int a = 0; a < n; ++a) {
        float* base = coarse.data() + a * s1 + b * s2;
        for (int i = 0; i < n; ++i) line[i] = base[i * s];
        wavelet_downsample(line.data(), half.data(), n, filter);
        wavelet_upsample(half.data(), line.data(), n);
        for (int i = 0; i < n; ++i) base[i * s] = line[i];
      }
    });
  }
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
