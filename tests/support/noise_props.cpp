// Helpers for the noise property tests: see noise_props.hpp.
#include "support/noise_props.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace nimbus::test {

void Moments::add(const Moments& o) {
  if (o.n > 0) {
    if (n == 0) {
      min = o.min;
      max = o.max;
    } else {
      min = o.min < min ? o.min : min;
      max = o.max > max ? o.max : max;
    }
  }
  n += o.n;
  sum += o.sum;
  sum2 += o.sum2;
  non_finite += o.non_finite;
}

double Moments::sd() const {
  if (n < 2) return 0.0;
  const double m = mean();
  const double var = (sum2 - double(n) * m * m) / double(n - 1);
  return var > 0.0 ? std::sqrt(var) : 0.0;
}

std::string Moments::str() const {
  char buf[200];
  std::snprintf(buf, sizeof buf, "n=%lld mean=%+.6f sd=%.6f min=%+.7f max=%+.7f non-finite=%lld",
                static_cast<long long>(n), mean(), sd(), double(min), double(max),
                static_cast<long long>(non_finite));
  return buf;
}

std::vector<std::array<double, 3>> random_points(Rng& rng, size_t count,
                                                 const std::array<double, 3>& lo,
                                                 const std::array<double, 3>& hi) {
  std::vector<std::array<double, 3>> pts(count);
  for (auto& p : pts)
    for (int a = 0; a < 3; ++a) p[a] = rng.uniform(lo[a], hi[a]);
  return pts;
}

Moments random_moments(const noise::NoiseField& field, int64_t total, uint64_t seed,
                       const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                       const BlockFn& per_block) {
  constexpr int64_t kBlock = int64_t(1) << 20;
  Rng rng(seed);
  Moments m;
  std::vector<float> values;
  for (int64_t done = 0; done < total; done += kBlock) {
    const size_t count = size_t(std::min(kBlock, total - done));
    const auto pts = random_points(rng, count, lo, hi);
    values.assign(count, 0.0f);
    noise::evaluate_points(field, pts, values);
    for (float v : values) m.add(v);
    if (per_block) per_block(pts, values);
  }
  return m;
}

Moments random_moments(const noise::NoiseField& field, int64_t total, uint64_t seed,
                       const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  return random_moments(field, total, seed, lo, hi, BlockFn{});
}

uint32_t bits(float v) {
  uint32_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

std::string describe(const noise::NoiseParams& p) {
  std::string s = std::string(noise::to_string(p.kind)) + "/" + std::string(noise::to_string(p.fractal));
  if (p.fractal != noise::Fractal::None) s += " octaves=" + std::to_string(p.octaves);
  char buf[160];
  std::snprintf(buf, sizeof buf, " freq=%g lac=%g gain=%g seed=%u", p.frequency, p.lacunarity,
                p.gain, p.seed);
  s += buf;
  if (p.time) {
    std::snprintf(buf, sizeof buf, " time=%g", *p.time);
    s += buf;
  }
  if (p.period[0] || p.period[1] || p.period[2])
    s += " period=" + std::to_string(p.period[0]) + "," + std::to_string(p.period[1]) + "," +
         std::to_string(p.period[2]);
  if (p.projected) {
    std::snprintf(buf, sizeof buf, " projected n=(%g,%g,%g)", p.normal[0], p.normal[1], p.normal[2]);
    s += buf;
  }
  return s;
}

}  // namespace nimbus::test
