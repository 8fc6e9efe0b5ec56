// The classic airlight of Sun et al.: A0 [F(A1, v1) - F(A1, gamma/2)] (eqs. 7-12) with F(u, v)
// (eq. 10) tabulated on an N x N grid and read bilinearly, kept to show its error beside the
// stable evaluation.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/core/quadrature.hpp"
#include "nimbus/render/media/airlight.hpp"

namespace nimbus::render {

namespace {
constexpr double kUMax = 10.0;                     // u range [0, 10] (Sun fig. 5)
constexpr double kVMax = 0.5 * std::numbers::pi;  // v range [0, pi/2]
}  // namespace

struct FTable::Impl {
  int n = 0;
  std::vector<double> values;  // row = v index, column = u index
  std::vector<float> floats;
};

FTable::FTable(int n) : n_(n) {
  if (n < 16 || n > 1024) throw std::invalid_argument("F table size must be in [16, 1024] (got " + std::to_string(n) + ")");
  auto impl = std::make_shared<Impl>();
  impl->n = n;
  impl->values.assign(size_t(n) * n, 0.0);
  // F(u, v_j) accumulated cell by cell along v, each cell integrated adaptively (Sun eq. 10).
  for (int i = 0; i < n; ++i) {
    const double u = kUMax * i / (n - 1);
    auto f = [u](double xi) {
      const double t = u * std::tan(xi);
      return t > 800.0 ? 0.0 : std::exp(-t);
    };
    double acc = 0.0;
    for (int j = 1; j < n; ++j) {
      const double v0 = kVMax * (j - 1) / (n - 1), v1 = kVMax * j / (n - 1);
      acc += u == 0.0 ? v1 - v0 : integrate_adaptive(f, v0, v1, {}, 1e-12, 1e-300).value;
      impl->values[size_t(j) * n + i] = acc;
    }
  }
  impl->floats.assign(impl->values.begin(), impl->values.end());
  impl_ = impl;
}

const float* FTable::data() const { return impl_->floats.data(); }

double FTable::lookup(double u, double v) const {
  if (std::isnan(u) || std::isnan(v)) return std::numeric_limits<double>::quiet_NaN();  // e.g. eq. 11 at beta = 0
  const int n = n_;
  const double fu = std::clamp(u / kUMax, 0.0, 1.0) * (n - 1);
  const double fv = std::clamp(v / kVMax, 0.0, 1.0) * (n - 1);
  const int i = std::min(static_cast<int>(fu), n - 2), j = std::min(static_cast<int>(fv), n - 2);
  const double du = fu - i, dv = fv - j;
  const auto& t = impl_->values;
  auto at = [&](int jj, int ii) { return t[size_t(jj) * n + ii]; };
  return (1.0 - dv) * ((1.0 - du) * at(j, i) + du * at(j, i + 1)) + dv * ((1.0 - du) * at(j + 1, i) + du * at(j + 1, i + 1));
}

double airlight_table(const AirlightQuery& q, const FTable& table) {
  validate(q);
  // Sun eqs. 7, 8, 11 and 12 as printed: no guard for sin(gamma) = 0 or beta = 0, lookups clamped
  // to the table's range.
  const double Tsv = q.beta * q.Dsv, Tvp = q.beta * q.Dvp;
  const double cg = std::cos(q.gamma), sg = std::sin(q.gamma);
  const double A0 = q.beta * q.beta * q.I0 * std::exp(-Tsv * cg) / (2.0 * std::numbers::pi * Tsv * sg);
  const double A1 = Tsv * sg;
  const double v1 = std::isinf(q.Dvp) ? 0.5 * std::numbers::pi
                                      : 0.25 * std::numbers::pi + 0.5 * std::atan((Tvp - Tsv * cg) / (Tsv * sg));
  return A0 * (table.lookup(A1, v1) - table.lookup(A1, 0.5 * q.gamma));
}

}  // namespace nimbus::render
