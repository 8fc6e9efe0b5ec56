// Power spectra for the spectral tests: see spectrum.hpp.
#include "support/spectrum.hpp"

#include <kissfft/kiss_fft.h>
#include <kissfft/kiss_fftr.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace nimbus::test {
namespace {

static_assert(sizeof(kiss_fft_scalar) == sizeof(float), "the float build of kissfft is expected");

// Periodic Hann window of length n (1 for n == 1).
std::vector<double> hann(int n, Window w) {
  std::vector<double> out(n, 1.0);
  if (w == Window::Hann && n > 1)
    for (int i = 0; i < n; ++i) out[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n);
  return out;
}

// Signed frequency index of FFT bin k of n (the Nyquist bin n/2 maps to -n/2; |f| is the same).
int signed_index(int k, int n) { return k < (n + 1) / 2 ? k : k - n; }

}  // namespace

PowerSpectrum::PowerSpectrum(std::span<const float> samples, std::array<int, 3> dims,
                             double spacing, Window window, bool remove_mean)
    : dims_(dims), spacing_(spacing) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  if (nx < 2 || ny < 2 || nz < 1 || nx % 2 != 0)
    throw std::invalid_argument("PowerSpectrum: need nx even >= 2, ny >= 2, nz >= 1");
  const size_t count = size_t(nx) * ny * nz;
  if (samples.size() != count) throw std::invalid_argument("PowerSpectrum: sample count != dims");
  if (!(spacing > 0.0)) throw std::invalid_argument("PowerSpectrum: spacing must be > 0");

  double mean = 0.0;
  if (remove_mean) {
    for (float v : samples) mean += v;
    mean /= double(count);
  }
  const auto wx = hann(nx, window), wy = hann(ny, window), wz = hann(nz, window);
  std::vector<kiss_fft_scalar> in(count);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y) {
      const size_t row = (size_t(z) * ny + y) * nx;
      const double wyz = wy[y] * wz[z];
      for (int x = 0; x < nx; ++x)
        in[row + x] = static_cast<kiss_fft_scalar>((double(samples[row + x]) - mean) * wyz * wx[x]);
    }

  // Real transform along x (nx / 2 + 1 bins), then complex transforms along y and z. Built
  // from 1D transforms because kiss_fftndr_alloc in Debian's kissfft 131.1.0-4.1~deb12u1
  // returns NULL for anything larger than about 52^2 (its overflow check, added for
  // CVE-2026-41445, is too strict: upstream mborgerding/kissfft#129).
  const int nxh = nx / 2 + 1;
  std::vector<kiss_fft_cpx> out(size_t(nz) * ny * nxh);
  {
    std::unique_ptr<std::remove_pointer_t<kiss_fftr_cfg>, void (*)(void*)> cfg(
        kiss_fftr_alloc(nx, 0, nullptr, nullptr), free);
    if (!cfg) throw std::runtime_error("kiss_fftr_alloc failed");
    for (size_t row = 0; row < size_t(nz) * ny; ++row)
      kiss_fftr(cfg.get(), in.data() + row * nx, out.data() + row * nxh);
  }
  // One complex pass along an axis of length n whose elements are `stride` apart, for each
  // line start in `starts`.
  auto pass = [&](int n, size_t stride, const std::vector<size_t>& starts) {
    if (n < 2) return;
    std::unique_ptr<std::remove_pointer_t<kiss_fft_cfg>, void (*)(void*)> cfg(
        kiss_fft_alloc(n, 0, nullptr, nullptr), free);
    if (!cfg) throw std::runtime_error("kiss_fft_alloc failed");
    std::vector<kiss_fft_cpx> a(n), b(n);
    for (size_t s0 : starts) {
      for (int i = 0; i < n; ++i) a[i] = out[s0 + i * stride];
      kiss_fft(cfg.get(), a.data(), b.data());
      for (int i = 0; i < n; ++i) out[s0 + i * stride] = b[i];
    }
  };
  std::vector<size_t> starts;
  for (int z = 0; z < nz; ++z)
    for (int kx = 0; kx < nxh; ++kx) starts.push_back(size_t(z) * ny * nxh + kx);
  pass(ny, nxh, starts);
  starts.clear();
  for (int y = 0; y < ny; ++y)
    for (int kx = 0; kx < nxh; ++kx) starts.push_back(size_t(y) * nxh + kx);
  pass(nz, size_t(ny) * nxh, starts);

  // Parseval: sum over all bins |X|^2 = N sum x^2; dividing by N^2 gives the mean square.
  const double norm = 1.0 / (double(count) * double(count));
  entries_.reserve(out.size());
  for (int kz = 0; kz < nz; ++kz)
    for (int ky = 0; ky < ny; ++ky)
      for (int kx = 0; kx < nxh; ++kx) {
        const kiss_fft_cpx c = out[(size_t(kz) * ny + ky) * nxh + kx];
        // Bins with 0 < kx < nx/2 stand for themselves and their mirror (-f), which the real
        // transform leaves out; kx == 0 and kx == nx/2 bins have their mirror in the output.
        const bool paired = kx != 0 && kx != nx / 2;
        Entry e;
        e.f[0] = static_cast<float>(kx / (nx * spacing));
        e.f[1] = static_cast<float>(signed_index(ky, ny) / (ny * spacing));
        e.f[2] = nz > 1 ? static_cast<float>(signed_index(kz, nz) / (nz * spacing)) : 0.0f;
        e.r = std::sqrt(e.f[0] * e.f[0] + e.f[1] * e.f[1] + e.f[2] * e.f[2]);
        e.mult = paired ? 2.0f : 1.0f;
        e.power = (double(c.r) * c.r + double(c.i) * c.i) * norm * e.mult;
        entries_.push_back(e);
      }
  finish();
}

void PowerSpectrum::finish() {
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    if (a.r != b.r) return a.r < b.r;
    for (int k = 0; k < 3; ++k)
      if (a.f[k] != b.f[k]) return a.f[k] < b.f[k];
    return false;
  });
  radii_.resize(entries_.size());
  for (size_t i = 0; i < entries_.size(); ++i) radii_[i] = entries_[i].r;
  update_prefix();
}

void PowerSpectrum::update_prefix() {
  prefix_.resize(entries_.size());
  double s = 0.0;
  for (size_t i = 0; i < entries_.size(); ++i) {
    s += entries_[i].power;
    prefix_[i] = s;
  }
}

void PowerSpectrum::accumulate(const PowerSpectrum& other) {
  if (other.dims_ != dims_ || other.spacing_ != spacing_ || other.entries_.size() != entries_.size())
    throw std::invalid_argument("PowerSpectrum::accumulate: different shape or spacing");
  // Same shape and spacing: the same frequencies in the same (total) order.
  for (size_t i = 0; i < entries_.size(); ++i) entries_[i].power += other.entries_[i].power;
  update_prefix();
}

double PowerSpectrum::energy(Band b) const {
  auto below = [&](double f) -> double {  // energy with r < f
    const size_t n = std::lower_bound(radii_.begin(), radii_.end(), f,
                                      [](float r, double v) { return double(r) < v; }) -
                     radii_.begin();
    return n == 0 ? 0.0 : prefix_[n - 1];
  };
  if (b.hi <= b.lo) return 0.0;
  return below(b.hi) - below(b.lo);
}

std::vector<double> PowerSpectrum::radial_histogram(double bin_width, double max_f) const {
  if (!(bin_width > 0.0)) throw std::invalid_argument("radial_histogram: bin_width must be > 0");
  if (max_f < 0.0) max_f = radii_.empty() ? 0.0 : double(radii_.back());
  const size_t bins = static_cast<size_t>(std::floor(max_f / bin_width)) + 1;
  std::vector<double> h(bins, 0.0);
  for (const Entry& e : entries_) {
    const size_t i = static_cast<size_t>(std::floor(double(e.r) / bin_width));
    if (i < bins) h[i] += e.power;
  }
  return h;
}

Band PowerSpectrum::best_octave(double max_lo) const {
  if (max_lo < 0.0) max_lo = 0.5 * nyquist();
  std::vector<double> candidates;
  candidates.reserve(2 * radii_.size());
  for (size_t i = 0; i < radii_.size(); ++i) {
    if (i > 0 && radii_[i] == radii_[i - 1]) continue;
    const double r = radii_[i];
    if (r <= 0.0) continue;
    if (r <= max_lo) candidates.push_back(r);
    if (0.5 * r <= max_lo) candidates.push_back(0.5 * r);
  }
  Band best{0.0, 0.0};
  double best_e = -1.0;
  for (double lo : candidates) {
    const double e = energy({lo, 2.0 * lo});
    if (e > best_e || (e == best_e && lo < best.lo)) {
      best_e = e;
      best = {lo, 2.0 * lo};
    }
  }
  return best;
}

ConeStats PowerSpectrum::cones(std::span<const std::array<double, 3>> directions,
                               double half_angle_deg, Band b) const {
  const double c = std::cos(half_angle_deg * std::numbers::pi / 180.0);
  std::vector<std::array<double, 3>> dirs;
  for (const auto& d : directions) {
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    dirs.push_back({d[0] / len, d[1] / len, d[2] / len});
  }
  const auto first = std::lower_bound(radii_.begin(), radii_.end(), b.lo,
                                      [](float r, double v) { return double(r) < v; }) -
                     radii_.begin();
  ConeStats s;
  for (size_t i = first; i < entries_.size() && double(entries_[i].r) < b.hi; ++i) {
    const Entry& e = entries_[i];
    if (e.r <= 0.0f) continue;
    const double per_bin = e.power / e.mult;
    for (const auto& d : dirs) {
      const double cosang = (e.f[0] * d[0] + e.f[1] * d[1] + e.f[2] * d[2]) / e.r;
      // This bin in the cone around d; its mirror -f (when it stands for one) when f lies in
      // the cone around -d.
      double bins = cosang >= c ? 1.0 : 0.0;
      if (e.mult == 2.0f && cosang <= -c) bins += 1.0;
      s.power += bins * per_bin;
      s.count += bins;
    }
  }
  return s;
}

const std::vector<std::array<double, 3>>& axis_directions() {
  static const std::vector<std::array<double, 3>> d = {
      {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  return d;
}

const std::vector<std::array<double, 3>>& diagonal_directions() {
  static const std::vector<std::array<double, 3>> d = [] {
    std::vector<std::array<double, 3>> v;
    const double s = 1.0 / std::sqrt(3.0);
    for (int i = 0; i < 8; ++i)
      v.push_back({(i & 1) ? -s : s, (i & 2) ? -s : s, (i & 4) ? -s : s});
    return v;
  }();
  return d;
}

double isotropy_ratio(const PowerSpectrum& s, Band b, double half_angle_deg) {
  const ConeStats axes = s.cones(axis_directions(), half_angle_deg, b);
  const ConeStats diag = s.cones(diagonal_directions(), half_angle_deg, b);
  return axes.density() / diag.density();
}

}  // namespace nimbus::test
