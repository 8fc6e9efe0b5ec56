// The tabulated surface airlight g = G0 e^{T} (1 + T) over (ln T, theta_s) for one phase function
// (surface_airlight.hpp),
// built in double, and the two ways of reading it: bilinear in double (the scene reference) and
// the float path of shaders/lib/surface_airlight.glsl compiled here as C++.
//
// Building: per column T, the gamma integral of G0 for every row at once. gamma's panels are
// the rows' spacing h = pi / (ny - 1); ny is odd, so pi/2 is a node and W's kinks |pi/2 -+ theta_j|,
// 3 pi/2 - theta_j fall on panel borders, where W is C^1 with a square-root second derivative.
// Each panel takes a Gauss rule (l evaluated once per node and reused for all rows), the first
// panel graded geometrically toward gamma = 0 (l sin(gamma) has a
// gamma ln gamma term there).
#include <glm/glm.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "nimbus/render/core/quadrature.hpp"
#include "nimbus/render/media/surface_airlight.hpp"

namespace nimbus::render::glsl {
using namespace glm;
#include "lib/surface_airlight.glsl"
}  // namespace nimbus::render::glsl

namespace nimbus::render {

namespace {

constexpr double kPi = std::numbers::pi;

// W from a = cos g cos t, b = sin g sin t (b^2 - a^2 = (b - a)(b + a), no cancellation).
double kernel_W(double a, double b) {
  if (b <= std::abs(a)) return 2.0 * kPi * std::max(a, 0.0);
  const double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return 2.0 * (a * phi0 + std::sqrt((b - a) * (b + a)));
}

// Nodes and weights of one panel [lo, hi]: the 7-point Gauss rule of quadrature.hpp's G7-K15
// pair (exact to degree 13) on the graded panels, the 3-point Gauss rule (degree 5) on the
// regular ones, which are narrow (pi / (ny - 1)) and hold no kink of W.
void add_panel(double lo, double hi, bool seven, std::vector<double>& nodes, std::vector<double>& weights) {
  const double c = 0.5 * (lo + hi), r = 0.5 * (hi - lo);
  if (!seven) {
    const double x = std::sqrt(0.6);
    for (const auto& [node, w] : {std::pair{-x, 5.0 / 9.0}, std::pair{0.0, 8.0 / 9.0}, std::pair{x, 5.0 / 9.0}}) {
      nodes.push_back(c + r * node);
      weights.push_back(r * w);
    }
    return;
  }
  for (int k = 0; k < 4; ++k) {
    const double x = gk15::kNode[2 * k + 1], w = gk15::kGauss[k];
    nodes.push_back(c - r * x);
    weights.push_back(r * w);
    if (x > 0.0) {
      nodes.push_back(c + r * x);
      weights.push_back(r * w);
    }
  }
}

}  // namespace

struct SurfaceAirlightTable::Impl {
  std::vector<double> values;  // row j (theta_s) major, column i (ln T)
  std::vector<float> floats;
};

namespace {

std::shared_ptr<const SurfaceAirlightTable::Impl> build(const Phase& phase, int nx, int ny) {
  auto impl = std::make_shared<SurfaceAirlightTable::Impl>();
  impl->values.assign(std::size_t(nx) * ny, 0.0);
  const double h = kPi / (ny - 1);
  std::vector<double> nodes, weights;
  double lo = h;
  for (int k = 0; k < 11; ++k) {  // [h 4^-(k+1), h 4^-k], then [0, h 4^-11]
    add_panel(0.25 * lo, lo, true, nodes, weights);
    lo *= 0.25;
  }
  add_panel(0.0, lo, true, nodes, weights);
  for (int k = 1; k < ny - 1; ++k) add_panel(k * h, (k + 1) * h, false, nodes, weights);
  // W(gamma_n, theta_j) does not depend on T: once, as a matrix (row j, node n).
  const std::size_t m = nodes.size();
  std::vector<double> W(std::size_t(ny) * m), sin_g(m);
  for (std::size_t n = 0; n < m; ++n) sin_g[n] = std::sin(nodes[n]);
  for (int j = 0; j < ny; ++j) {
    const double theta = j * h, ct = std::cos(theta), st = std::sin(theta);
    for (std::size_t n = 0; n < m; ++n) W[j * m + n] = kernel_W(std::cos(nodes[n]) * ct, sin_g[n] * st);
  }
  const double ln_lo = std::log(SurfaceAirlightTable::kTMin), ln_hi = std::log(SurfaceAirlightTable::kTMax);
  tbb::parallel_for(tbb::blocked_range<int>(0, nx), [&](const tbb::blocked_range<int>& range) {
    std::vector<double> lw(nodes.size());
    for (int i = range.begin(); i != range.end(); ++i) {
      const double T = std::exp(ln_lo + (ln_hi - ln_lo) * i / (nx - 1));
      for (std::size_t n = 0; n < nodes.size(); ++n) lw[n] = surface_airlight_l(T, nodes[n], phase) * sin_g[n] * weights[n];
      const double scale = std::exp(T) * (1.0 + T);
      for (int j = 0; j < ny; ++j) {
        double sum = 0.0;
        for (std::size_t n = 0; n < m; ++n) sum += lw[n] * W[j * m + n];
        impl->values[std::size_t(j) * nx + i] = sum * scale;
      }
    }
  });
  impl->floats.assign(impl->values.begin(), impl->values.end());
  return impl;
}

}  // namespace

SurfaceAirlightTable::SurfaceAirlightTable(const Phase& phase, int nx, int ny) : phase_(phase), nx_(nx), ny_(ny) {
  if (nx < 8 || nx > 1024) throw std::invalid_argument("surface airlight table nx must be in [8, 1024] (got " + std::to_string(nx) + ")");
  if (ny < 9 || ny > 2049 || ny % 2 == 0)
    throw std::invalid_argument("surface airlight table ny must be odd and in [9, 2049] (got " + std::to_string(ny) + ")");
  static std::mutex mutex;
  validate(phase, "surface airlight table phase");
  if (phase.kind == PhaseKind::DualHenyeyGreenstein)  // its cache holds one lobe per (kind, g)
    throw std::invalid_argument("surface airlight table phase " + to_string(phase) + ": the fog's table takes one lobe");
  static std::map<std::tuple<int, int, int, double>, std::shared_ptr<const Impl>> built;
  const std::lock_guard<std::mutex> lock(mutex);
  const double g = phase_takes_g(phase.kind) ? phase.g : 0.0;
  auto& slot = built[{nx, ny, static_cast<int>(phase.kind), g}];
  if (!slot) slot = build(phase, nx, ny);
  impl_ = slot;
}

double SurfaceAirlightTable::node(int i, int j) const { return impl_->values.at(std::size_t(j) * nx_ + i); }
const float* SurfaceAirlightTable::data() const { return impl_->floats.data(); }

double SurfaceAirlightTable::G0(double T, double theta_s) const {
  const double lo = std::log(kTMin);
  const double fx = std::clamp((std::log(std::clamp(T, kTMin, kTMax)) - lo) / (std::log(kTMax) - lo), 0.0, 1.0) * (nx_ - 1);
  const double fy = std::clamp(theta_s / kPi, 0.0, 1.0) * (ny_ - 1);
  const int i = std::min(static_cast<int>(fx), nx_ - 2), j = std::min(static_cast<int>(fy), ny_ - 2);
  const double dx = fx - i, dy = fy - j;
  const double g = (1.0 - dy) * ((1.0 - dx) * node(i, j) + dx * node(i + 1, j)) +
                   dy * ((1.0 - dx) * node(i, j + 1) + dx * node(i + 1, j + 1));
  return g * std::exp(-T) / (1.0 + T);
}

double surface_airlight_table(const SurfaceAirlightQuery& q, const SurfaceAirlightTable& table) {
  validate(q);
  if (q.sigma_s == 0.0 || q.I0 == 0.0 || q.albedo == 0.0) return 0.0;
  return q.albedo / kPi * (q.sigma_s * q.I0 / q.Dsp) * table.G0(q.sigma_t * q.Dsp, std::acos(q.cos_theta_s));
}

double surface_airlight_float(const SurfaceAirlightQuery& q, const SurfaceAirlightTable& table) {
  validate(q);
  const int nx = table.nx(), ny = table.ny();
  const float* g = table.data();
  const float D = std::max(float(q.Dsp), 1.0e-20f);
  const glm::vec2 f = glsl::surface_airlight_coords(std::max(float(q.sigma_t), 0.0f) * D, float(q.cos_theta_s), nx, ny);
  const glm::ivec2 c = glsl::surface_airlight_cell(f, nx, ny);
  auto at = [&](int i, int j) { return g[std::size_t(j) * nx + i]; };
  const float gi = glsl::surface_airlight_bilinear(f, c, at(c.x, c.y), at(c.x + 1, c.y), at(c.x, c.y + 1), at(c.x + 1, c.y + 1));
  return float(q.albedo) * glsl::surface_airlight_radiance(float(q.sigma_t), float(q.sigma_s), float(q.I0), float(q.Dsp), gi);
}

}  // namespace nimbus::render
