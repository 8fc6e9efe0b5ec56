// NoiseField: per-octave constants, the scalar path, analytic gradients and the predicted
// statistics of each kind.
#include "nimbus/noise/field.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "kernels.hpp"

namespace nimbus::noise {
namespace {

using B1 = simd::Batch<1>;

int wrap_int(int64_t i, int n) { return static_cast<int>(((i % n) + n) % n); }

// Integer lattice offset in [0, n)^3, decorrelating octaves and time slices of one tile.
void tile_offset(uint32_t seed, int64_t slice, int n, int32_t out[3]) {
  uint32_t h = hash::mix<uint32_t>(seed ^ hash::mix<uint32_t>(static_cast<uint32_t>(slice) ^
                                   hash::mix<uint32_t>(static_cast<uint32_t>(slice >> 32) + 0x5bd1e995u)));
  for (int a = 0; a < 3; ++a) {
    out[a] = static_cast<int32_t>(h % static_cast<uint32_t>(n));
    h = hash::mix<uint32_t>(h + 0x68e31da4u);
  }
}

double simpson(auto f, int intervals = 4096) {
  const double h = 1.0 / intervals;
  double s = f(0.0) + f(1.0);
  for (int i = 1; i < intervals; ++i) s += f(i * h) * ((i % 2) ? 4.0 : 2.0);
  return s * h / 3.0;
}

double fade_d(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
double dfade_d(double t) { return 30.0 * t * t * (t - 1.0) * (t - 1.0); }

// A = E_t[(1-s)^2 + s^2] and B = E_t[(1-s)^2 t^2 + s^2 (1-t)^2] for the quintic fade s(t).
double weight_A() {
  return simpson([](double t) { const double s = fade_d(t); return (1 - s) * (1 - s) + s * s; });
}
double weight_B() {
  return simpson([](double t) {
    const double s = fade_d(t);
    return (1 - s) * (1 - s) * t * t + s * s * (1 - t) * (1 - t);
  });
}

// The quadratic B-spline centred at 0 (support (-1.5, 1.5)).
double bspline2(double x) {
  x = std::fabs(x);
  if (x < 0.5) return 0.75 - x * x;
  if (x < 1.5) return 0.5 * (1.5 - x) * (1.5 - x);
  return 0.0;
}

}  // namespace

namespace detail {

// Projected evaluation (Cook & DeRose section 3.4): the basis function of coefficient c is
// evaluated at c moved towards the sample's plane along the normal, by the fraction
// 1 - 1/k, i.e. at x = p - c - (1 - 1/k) n (n.(p-c)). Along the normal that is B2(d / k): the
// slice averages the 3D noise with a B-spline k times wider, which multiplies the spectrum
// by sinc^3(k f_n) and removes the out-of-plane frequencies that would alias into low
// in-plane ones. C&D move halfway (k = 2); nimbus uses k = kProjectionStretch = 3, which
// cuts the power left at f_n = 1/4 from 6.6 % to 0.07 % (measured slice leakage: docs).
// For |x_i| < 1.5 we need |p_i - c_i| < 1.5 + 2.6 (k - 1) |n_i|. The result is divided by
// the sum of the weights, so it stays a convex combination of tile coefficients (in
// [-1, 1]); for axis-aligned normals that sum is exactly k.
float wavelet_projected(const detail::FieldData& fd, const detail::OctaveData& o, double x,
                        double y, double z) {
  const int n = fd.tile_n;
  const double p[3] = {x, y, z};
  const double* nv = fd.normal;
  int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double r = 1.5 + 2.6 * (kProjectionStretch - 1.0) * std::fabs(nv[a]);
    lo[a] = static_cast<int64_t>(std::ceil(p[a] - r));
    hi[a] = static_cast<int64_t>(std::floor(p[a] + r));
  }
  double total = 0.0;
  for (int s = 0; s < o.slices; ++s) {
    double sum = 0.0, wsum = 0.0;
    for (int64_t cz = lo[2]; cz <= hi[2]; ++cz) {
      for (int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
        for (int64_t cx = lo[0]; cx <= hi[0]; ++cx) {
          const double d[3] = {p[0] - double(cx), p[1] - double(cy), p[2] - double(cz)};
          const double dot = nv[0] * d[0] + nv[1] * d[1] + nv[2] * d[2];
          const double move = (1.0 - 1.0 / kProjectionStretch) * dot;
          const double w = bspline2(d[0] - move * nv[0]) * bspline2(d[1] - move * nv[1]) *
                           bspline2(d[2] - move * nv[2]);
          if (w == 0.0) continue;
          const int ix = wrap_int(cx + o.slice_offset[s][0], n);
          const int iy = wrap_int(cy + o.slice_offset[s][1], n);
          const int iz = wrap_int(cz + o.slice_offset[s][2], n);
          sum += w * fd.tile[(size_t(iz) * n + iy) * n + ix];
          wsum += w;
        }
      }
    }
    const double v = wsum > 0.0 ? sum / wsum : 0.0;
    total += (o.slices == 1 ? 1.0 : double(o.slice_weight[s])) * v;
  }
  return static_cast<float>(total);
}

}  // namespace detail

NoiseField::NoiseField(const NoiseParams& p) : params_(p) {
  validate(p);
  // Normalise the projection normal.
  const double len = std::sqrt(p.normal[0] * p.normal[0] + p.normal[1] * p.normal[1] +
                               p.normal[2] * p.normal[2]);
  for (int a = 0; a < 3; ++a) params_.normal[a] = p.normal[a] / len;

  data_.kind = p.kind;
  data_.fractal = p.fractal;
  data_.animated = p.time.has_value();
  data_.octaves = p.fractal == Fractal::None ? 1 : p.octaves;
  data_.projected = p.projected;
  for (int a = 0; a < 3; ++a) data_.normal[a] = params_.normal[a];
  if (p.kind == Kind::Wavelet) {
    const int n = p.tile_size > 0 ? p.tile_size : (p.period[0] > 0 ? p.period[0] : 128);
    tile_ = WaveletTile::shared(n, p.seed);
    data_.tile = tile_->data();
    data_.tile_n = n;
  }
  double amp = 1.0, amp_sum = 0.0, ratio = 1.0;
  for (int i = 0; i < data_.octaves; ++i) {
    detail::OctaveData& o = data_.oct[i];
    o.freq = p.frequency * ratio;
    o.time = p.time.value_or(0.0) * ratio;
    o.amp = static_cast<float>(amp);
    o.seed = hash::octave_seed(p.seed, i);
    o.cell_time = static_cast<float>(o.time - 8.0 * std::floor(o.time / 8.0));
    if (data_.animated) {
      // Value noise blends two time slices with the fade s of the time fraction; this factor
      // makes its variance independent of time (see kernels::value4). It is computed from the
      // same float fraction and fade the kernel uses.
      const float tf = static_cast<float>(o.time - std::floor(o.time));
      const double s = kernels::fade(tf);
      o.time_norm = static_cast<float>(1.0 / (std::sqrt(2.0 * ((1 - s) * (1 - s) + s * s))));
    }
    for (int a = 0; a < 3; ++a) {
      o.period[a] = p.period[a] > 0 ? double(p.period[a]) * ratio : 0.0;
      o.iperiod[a] = static_cast<int32_t>(o.period[a]);
    }
    if (p.kind == Kind::Wavelet) {
      const int n = data_.tile_n;
      int32_t base[3];
      tile_offset(o.seed, 0x7fffffff, n, base);
      if (!data_.animated) {
        o.slices = 1;
        for (int a = 0; a < 3; ++a) o.slice_offset[0][a] = base[a];
      } else {
        // Quadratic B-spline blend over integer time slices, each an independently offset
        // copy of the tile. Dividing by sqrt(sum w^2) keeps the variance constant in time;
        // the extra 1/sqrt(2) bounds the result by 1 (sum w / sqrt(sum w^2) <= sqrt(2)).
        const double c = std::floor(o.time + 0.5);
        const double t = o.time - c;
        const double w[3] = {0.5 * (0.5 - t) * (0.5 - t), 0.75 - t * t, 0.5 * (0.5 + t) * (0.5 + t)};
        const double norm = 1.0 / (std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * std::sqrt(2.0));
        o.slices = 3;
        for (int s = 0; s < 3; ++s) {
          o.slice_weight[s] = static_cast<float>(w[s] * norm);
          int32_t off[3];
          tile_offset(o.seed, static_cast<int64_t>(c) + s - 1, n, off);
          for (int a = 0; a < 3; ++a) o.slice_offset[s][a] = (base[a] + off[a]) % n;
        }
      }
    }
    amp_sum += amp;
    amp *= p.gain;
    ratio *= p.lacunarity;
  }
  data_.inv_amp_sum = static_cast<float>(1.0 / amp_sum);
}

float NoiseField::eval(double x, double y, double z) const {
  return kernels::field<B1>(data_, x, y, z);
}

Range NoiseField::range() const {
  switch (params_.fractal) {
    case Fractal::Turbulence:
    case Fractal::Ridged: return {0.0f, 1.0f};
    default: return {-1.0f, 1.0f};
  }
}

double NoiseField::single_octave_sd() const {
  const double A = weight_A(), Bw = weight_B();
  const bool four = data_.animated;
  switch (params_.kind) {
    case Kind::Value:  // lattice values uniform in (-1, 1): variance 1/3
      // Animated: two independent time slices, renormalised to the variance of one, halved.
      return std::sqrt(A * A * A / 3.0 * (four ? 0.5 : 1.0));
    case Kind::Gradient:
      // E[g g^T] = (2/3) I for the 12 cube edges, (3/4) I for the 32 tesseract edges, so
      // var = (2/3) sum_c E[w_c^2 |d_c|^2] = 2 B A^2 in 3D, and 3 B A^3 in 4D.
      // In 4D the time fraction t is the same for every sample, so with W_t = (1-s)^2 + s^2
      // and D_t = (1-s)^2 t^2 + s^2 (1-t)^2:  var = (3/4) (W_t 3 B A^2 + D_t A^3).
      if (four) {
        const double t = data_.oct[0].time - std::floor(data_.oct[0].time), s = fade_d(t);
        const double Wt = (1 - s) * (1 - s) + s * s;
        const double Dt = (1 - s) * (1 - s) * t * t + s * s * (1 - t) * (1 - t);
        return std::sqrt(0.75 * (Wt * 3.0 * Bw * A * A + Dt * A * A * A)) * kGradientScale4;
      }
      return std::sqrt(2.0 * Bw * A * A) * kGradientScale3;
    case Kind::Worley:  // the points are uniform in their cells at every time
      return kWorleySdF1;
    case Kind::Wavelet: {
      if (params_.projected) return std::numeric_limits<double>::quiet_NaN();
      std::call_once(sd_once_, [this] {
        // var = sum over lags d of C(d) * prod_a B5(d_a), where C is the tile's circular
        // autocovariance and B5(d) = integral of B2(x) B2(x - d) = (1, 26, 66, 26, 1) / 120.
        const double b5[5] = {1.0 / 120, 26.0 / 120, 66.0 / 120, 26.0 / 120, 1.0 / 120};
        const int n = data_.tile_n;
        const float* t = data_.tile;
        double var = 0.0;
        for (int dz = -2; dz <= 2; ++dz)
          for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
              double c = 0.0;
              for (int z = 0; z < n; ++z) {
                const int z2 = wrap_int(z + dz, n);
                for (int y = 0; y < n; ++y) {
                  const int y2 = wrap_int(y + dy, n);
                  const float* r1 = t + (size_t(z) * n + y) * n;
                  const float* r2 = t + (size_t(z2) * n + y2) * n;
                  for (int x = 0; x < n; ++x) {
                    int x2 = x + dx;
                    x2 += x2 < 0 ? n : (x2 >= n ? -n : 0);
                    c += double(r1[x]) * r2[x2];
                  }
                }
              }
              var += c / (double(n) * n * n) * b5[dx + 2] * b5[dy + 2] * b5[dz + 2];
            }
        wavelet_var_ = var;
      });
      return std::sqrt(four ? 0.5 * wavelet_var_ : wavelet_var_);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double NoiseField::expected_mean() const {
  if (params_.kind != Kind::Worley) return 0.0;
  if (params_.fractal == Fractal::None || params_.fractal == Fractal::Fbm) return 1.0 - kWorleyMeanF1;
  return std::numeric_limits<double>::quiet_NaN();
}

double NoiseField::expected_sd() const {
  switch (params_.fractal) {
    case Fractal::None: return single_octave_sd();
    case Fractal::Fbm: {  // octaves are independent: sd = sd1 * sqrt(sum a^2) / sum a
      double s1 = 0.0, s2 = 0.0;
      for (int i = 0; i < data_.octaves; ++i) {
        s1 += data_.oct[i].amp;
        s2 += double(data_.oct[i].amp) * data_.oct[i].amp;
      }
      return single_octave_sd() * std::sqrt(s2) / s1;
    }
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

// ---- Analytic gradients ------------------------------------------------------------------

namespace {

// Value and lattice-space gradient of one octave of value or gradient noise (3D).
void octave_gradient(const detail::FieldData& fd, const detail::OctaveData& o, double x,
                     double y, double z, double out[4]) {
  using kernels::Axis;
  const double X = x * o.freq, Y = y * o.freq, Z = z * o.freq;
  Axis<B1> a[3] = {kernels::split<B1>(X, o.period[0], o.iperiod[0], hash::kPrimeX),
                   kernels::split<B1>(Y, o.period[1], o.iperiod[1], hash::kPrimeY),
                   kernels::split<B1>(Z, o.period[2], o.iperiod[2], hash::kPrimeZ)};
  double t[3], s[3], ds[3];
  for (int k = 0; k < 3; ++k) {
    t[k] = a[k].t;
    s[k] = fade_d(t[k]);
    ds[k] = dfade_d(t[k]);
  }
  double v = 0.0, g[3] = {0, 0, 0};
  for (int c = 0; c < 8; ++c) {
    const uint32_t h = kernels::corner_hash<B1>(a, c, o.seed);
    double w[3], dw[3], d[3];
    for (int k = 0; k < 3; ++k) {
      const bool hi = (c >> k) & 1;
      w[k] = hi ? s[k] : 1.0 - s[k];
      dw[k] = hi ? ds[k] : -ds[k];
      d[k] = hi ? t[k] - 1.0 : t[k];
    }
    const double wc = w[0] * w[1] * w[2];
    const double dwc[3] = {dw[0] * w[1] * w[2], w[0] * dw[1] * w[2], w[0] * w[1] * dw[2]};
    if (fd.kind == Kind::Value) {
      const double val = kernels::lattice_value<B1>(h);
      v += wc * val;
      for (int k = 0; k < 3; ++k) g[k] += dwc[k] * val;
    } else {
      float gv[3];
      edge_gradient3(static_cast<int>(kernels::edge_index3(h)), gv);
      const double dot = gv[0] * d[0] + gv[1] * d[1] + gv[2] * d[2];
      v += wc * dot;
      for (int k = 0; k < 3; ++k) g[k] += dwc[k] * dot + wc * gv[k];
    }
  }
  const double scale = fd.kind == Kind::Gradient ? double(kGradientScale3) : 1.0;
  out[0] = v * scale;
  for (int k = 0; k < 3; ++k) out[k + 1] = g[k] * scale * o.freq;  // per input unit
}

}  // namespace

NoiseGradient NoiseField::eval_gradient(double x, double y, double z) const {
  if (params_.kind == Kind::Wavelet || params_.kind == Kind::Worley || data_.animated)
    throw std::logic_error("analytic gradients exist for value and gradient noise, not animated");
  double acc[4] = {0, 0, 0, 0};
  for (int i = 0; i < data_.octaves; ++i) {
    const detail::OctaveData& o = data_.oct[i];
    double r[4];
    octave_gradient(data_, o, x, y, z, r);
    if (params_.fractal == Fractal::None) {
      return {static_cast<float>(r[0]), static_cast<float>(r[1]), static_cast<float>(r[2]),
              static_cast<float>(r[3])};
    }
    const double sgn = r[0] < 0 ? -1.0 : 1.0;
    double f = 0.0, df = 0.0;  // f(n) and f'(n) of this fractal's fold
    switch (params_.fractal) {
      case Fractal::Fbm: f = r[0]; df = 1.0; break;
      case Fractal::Turbulence: f = std::fabs(r[0]); df = sgn; break;
      case Fractal::Ridged: f = (1 - std::fabs(r[0])) * (1 - std::fabs(r[0])); df = -2.0 * (1 - std::fabs(r[0])) * sgn; break;
      case Fractal::None: break;
    }
    acc[0] += o.amp * f;
    for (int k = 1; k < 4; ++k) acc[k] += o.amp * df * r[k];
  }
  const double inv = data_.inv_amp_sum;
  return {static_cast<float>(acc[0] * inv), static_cast<float>(acc[1] * inv),
          static_cast<float>(acc[2] * inv), static_cast<float>(acc[3] * inv)};
}

std::array<double, 3> worley_feature_point(const NoiseField& field, int octave, int64_t cx, int64_t cy,
                                           int64_t cz) {
  const detail::FieldData& fd = field.data();
  if (fd.kind != Kind::Worley) throw std::invalid_argument("worley_feature_point: the field is not Worley noise");
  if (octave < 0 || octave >= fd.octaves) throw std::invalid_argument("worley_feature_point: no such octave");
  const detail::OctaveData& o = fd.oct[octave];
  const int64_t c[3] = {cx, cy, cz};
  const uint32_t prime[3] = {hash::kPrimeX, hash::kPrimeY, hash::kPrimeZ};
  uint32_t h[3];
  for (int a = 0; a < 3; ++a) {
    int64_t w = c[a];
    if (o.iperiod[a] > 0) w = ((w % o.iperiod[a]) + o.iperiod[a]) % o.iperiod[a];
    h[a] = static_cast<uint32_t>(static_cast<uint64_t>(w)) * prime[a];
  }
  float p[3];
  kernels::cell_point<B1>(h[0], h[1], h[2], o.seed, fd.animated, o.cell_time, p);
  return {double(cx) + p[0], double(cy) + p[1], double(cz) + p[2]};
}

// ---- Single-octave helpers --------------------------------------------------------------

namespace {
NoiseField& cached_field(Kind kind, bool animated, uint32_t seed, double t) {
  thread_local NoiseParams last{};
  thread_local std::unique_ptr<NoiseField> field;
  NoiseParams p;
  p.kind = kind;
  p.seed = seed;
  if (animated) p.time = t;
  if (!field || last.kind != p.kind || last.seed != p.seed || last.time != p.time) {
    field = std::make_unique<NoiseField>(p);
    last = p;
  }
  return *field;
}
}  // namespace

float value_noise(double x, double y, double z, uint32_t seed) {
  return cached_field(Kind::Value, false, seed, 0.0).eval(x, y, z);
}
float value_noise(double x, double y, double z, double t, uint32_t seed) {
  return cached_field(Kind::Value, true, seed, t).eval(x, y, z);
}
float gradient_noise(double x, double y, double z, uint32_t seed) {
  return cached_field(Kind::Gradient, false, seed, 0.0).eval(x, y, z);
}
float gradient_noise(double x, double y, double z, double t, uint32_t seed) {
  return cached_field(Kind::Gradient, true, seed, t).eval(x, y, z);
}

float gradient_noise_cell(const float t[3], const int index[8]) {
  uint32_t idx[8];
  for (int k = 0; k < 8; ++k) idx[k] = static_cast<uint32_t>(index[k]);
  return kernels::gradient3_cell<B1>(idx, t[0], t[1], t[2]);
}

float gradient_noise_cell4(const float t[4], const int index[16]) {
  uint32_t idx[16];
  for (int k = 0; k < 16; ++k) idx[k] = static_cast<uint32_t>(index[k]);
  return kernels::gradient4_cell<B1>(idx, t[0], t[1], t[2], t[3]);
}

void edge_gradient3(int index, float g[3]) {
  const int pair = index >> 2;
  const float su = (index & 1) ? -1.0f : 1.0f, sv = (index & 2) ? -1.0f : 1.0f;
  g[0] = g[1] = g[2] = 0.0f;
  // u is x unless the pair is yz; v is y for the xy pair, else z (as in edge_dot3).
  g[pair == 2 ? 1 : 0] = su;
  g[pair == 0 ? 1 : 2] = sv;
}

}  // namespace nimbus::noise
