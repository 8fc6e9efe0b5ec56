// Smoothness: the quintic-fade noises are C2 across cell faces, and the analytic gradients
// (NoiseField::eval_gradient) agree with central differences of NoiseField::eval.
//
// Why the second derivative is not taken as a plain second difference of eval() at h = 1e-3:
// eval() returns a float, so each value carries a rounding error of up to ~3e-8 and the
// second difference (f(x+h) - 2 f(x) + f(x-h)) / h^2 an error of up to ~0.1, while the
// criterion is 1e-3 of the RMS second derivative (~2.5e-3). Two estimators that reach it:
//  1. Along a line parallel to an axis, value noise is a polynomial of degree 5 and gradient
//     noise of degree 6 in the coordinate inside each cell. A least-squares polynomial of
//     degree 7 through 400 samples of eval() on each side of a face gives the one-sided
//     second derivatives at the face with errors ~1e-5, and its residual shows that eval()
//     really is that polynomial.
//  2. The analytic gradient (eval_gradient, computed in double and rounded to float) is
//     differenced at h = 1e-3 with second-order one-sided stencils on each side of the face;
//     its rounding error there is ~1e-4.
// Both also run on a deliberately C1-only function (cubic smoothstep), which they must flag.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::Rng;

// Least-squares polynomial of degree `deg` in u = (x - x0) / w on samples (u_i, y_i), solved
// by normal equations in double (Legendre-like conditioning is not needed for deg <= 8 on
// [-1, 1]). Returns the coefficients c_0..c_deg and the max residual.
struct Fit {
  std::vector<double> c;
  double max_residual = 0.0;
  double eval(double u) const {
    double s = 0.0;
    for (int k = int(c.size()) - 1; k >= 0; --k) s = s * u + c[k];
    return s;
  }
  double second(double u) const {  // d^2/du^2
    double s = 0.0;
    for (int k = int(c.size()) - 1; k >= 2; --k) s = s * u + c[k] * k * (k - 1);
    return s;
  }
};

Fit fit_poly(const std::vector<double>& u, const std::vector<double>& y, int deg) {
  const int m = deg + 1;
  std::vector<double> A(size_t(m) * m, 0.0), b(m, 0.0);
  for (size_t i = 0; i < u.size(); ++i) {
    std::vector<double> pw(2 * m, 1.0);
    for (int k = 1; k < 2 * m; ++k) pw[k] = pw[k - 1] * u[i];
    for (int r = 0; r < m; ++r) {
      b[r] += pw[r] * y[i];
      for (int c = 0; c < m; ++c) A[r * m + c] += pw[r + c];
    }
  }
  // Gaussian elimination with partial pivoting.
  for (int c = 0; c < m; ++c) {
    int piv = c;
    for (int r = c + 1; r < m; ++r)
      if (std::fabs(A[r * m + c]) > std::fabs(A[piv * m + c])) piv = r;
    for (int k = 0; k < m; ++k) std::swap(A[c * m + k], A[piv * m + k]);
    std::swap(b[c], b[piv]);
    for (int r = c + 1; r < m; ++r) {
      const double f = A[r * m + c] / A[c * m + c];
      for (int k = c; k < m; ++k) A[r * m + k] -= f * A[c * m + k];
      b[r] -= f * b[c];
    }
  }
  Fit fit;
  fit.c.assign(m, 0.0);
  for (int r = m - 1; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < m; ++k) s -= A[r * m + k] * fit.c[k];
    fit.c[r] = s / A[r * m + r];
  }
  for (size_t i = 0; i < u.size(); ++i)
    fit.max_residual = std::max(fit.max_residual, std::fabs(fit.eval(u[i]) - y[i]));
  return fit;
}

// A line through a face: f(s) for s in [-1, 1], the face at s = 0 (one cell on each side).
using LineFn = std::function<float(double s)>;

struct FaceJump {
  double jump = 0.0;         // |f''(0+) - f''(0-)|
  double sum_sq_second = 0;  // sum of f''^2 over the samples (both cells)
  int samples = 0;
  double max_residual = 0.0;
};

// Estimator 1: a degree-7 fit per cell, samples strictly inside each cell.
FaceJump jump_by_fit(const LineFn& f) {
  const int n = 400, deg = 7;
  FaceJump r;
  double second_at_face[2];
  for (int side = 0; side < 2; ++side) {
    std::vector<double> u(n), y(n);
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) / n;  // (0, 1) inside the cell
      const double s = side == 0 ? -t : t;
      u[i] = 2.0 * t - 1.0;  // the cell mapped onto [-1, 1]; the face is at u = -1
      y[i] = f(s);
    }
    const Fit fit = fit_poly(u, y, deg);
    // d^2/ds^2 = 4 d^2/du^2 (u = 2t - 1, t = |s|; the sign of ds/dt drops out when squared).
    second_at_face[side] = 4.0 * fit.second(-1.0);
    for (int i = 0; i < n; ++i) {
      const double d2 = 4.0 * fit.second(u[i]);
      r.sum_sq_second += d2 * d2;
      ++r.samples;
    }
    r.max_residual = std::max(r.max_residual, fit.max_residual);
  }
  r.jump = std::fabs(second_at_face[1] - second_at_face[0]);
  return r;
}

// Estimator 2: one-sided second-order differences (h = 1e-3) of a derivative g = f' at the
// face: f''(0-) ~ (3 g(0) - 4 g(-h) + g(-2h)) / (2h), f''(0+) ~ (-3 g(0) + 4 g(h) - g(2h)) / (2h).
using DerivFn = std::function<double(double s)>;
double jump_by_gradient_differences(const DerivFn& g, double h) {
  const double left = (3.0 * g(0.0) - 4.0 * g(-h) + g(-2.0 * h)) / (2.0 * h);
  const double right = (-3.0 * g(0.0) + 4.0 * g(h) - g(2.0 * h)) / (2.0 * h);
  return std::fabs(right - left);
}

struct LineSpec {
  int axis;             // the line runs along this axis
  double face;          // integer coordinate of the face crossed
  double other[3];      // the other two coordinates (entries on `axis` ignored)
  std::array<double, 3> at(double s) const {
    std::array<double, 3> p{other[0], other[1], other[2]};
    p[axis] = face + s;
    return p;
  }
};

std::vector<LineSpec> random_lines(int count, uint64_t seed) {
  Rng rng(seed);
  std::vector<LineSpec> lines;
  for (int i = 0; i < count; ++i) {
    LineSpec l;
    l.axis = i % 3;
    l.face = double(rng.integer(-500, 500));
    for (double& o : l.other) o = rng.uniform(-500.0, 500.0);
    lines.push_back(l);
  }
  return lines;
}

// Synthetic C1-only noise along a line: cubic smoothstep interpolation of random values.
float c1_reference(double s, uint64_t seed) {
  const double c = std::floor(s), t = s - c;
  Rng a(seed * 131 + uint64_t(int64_t(c) + 1000)), b(seed * 131 + uint64_t(int64_t(c) + 1001));
  const double v0 = a.uniform(-1, 1), v1 = b.uniform(-1, 1);
  const double w = t * t * (3.0 - 2.0 * t);
  return static_cast<float>(v0 + w * (v1 - v0));
}

TEST(NoisePropsSmooth, FitDetectsAC1OnlyFunction) {
  // The estimator must flag a jump of the second derivative where there is one.
  double worst_ratio = 1e300;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const FaceJump j = jump_by_fit([seed](double s) { return c1_reference(s, seed); });
    const double rms = std::sqrt(j.sum_sq_second / j.samples);
    worst_ratio = std::min(worst_ratio, j.jump / rms);
  }
  std::printf("C1 reference: smallest second-derivative jump / RMS = %.3f\n", worst_ratio);
  EXPECT_GT(worst_ratio, 1e-2);
}

class NoisePropsSmoothKind : public ::testing::TestWithParam<Kind> {};

TEST_P(NoisePropsSmoothKind, SecondDerivativeIsContinuousAcrossFaces_Fit) {
  NoiseParams p;
  p.kind = GetParam();
  p.seed = 17;
  const NoiseField field(p);
  double max_jump = 0.0, sum_sq = 0.0, max_res = 0.0;
  int samples = 0;
  for (const LineSpec& l : random_lines(60, 5)) {
    const FaceJump j = jump_by_fit([&](double s) {
      const auto q = l.at(s);
      return field.eval(q[0], q[1], q[2]);
    });
    max_jump = std::max(max_jump, j.jump);
    sum_sq += j.sum_sq_second;
    samples += j.samples;
    max_res = std::max(max_res, j.max_residual);
  }
  const double rms = std::sqrt(sum_sq / samples);
  std::printf("%s (fit): RMS f'' %.4f, max jump %.3g (%.3g of RMS), max fit residual %.3g\n",
              std::string(to_string(p.kind)).c_str(), rms, max_jump, max_jump / rms, max_res);
  RecordProperty("rms_second", std::to_string(rms));
  RecordProperty("max_jump", std::to_string(max_jump));
  EXPECT_GT(rms, 0.5);  // not degenerate
  EXPECT_LE(max_jump, 1e-3 * rms);
  // Inside a cell, eval() along an axis is the documented polynomial (up to float rounding,
  // measured ~1.4e-6 at most).
  EXPECT_LE(max_res, 1e-5);
}

TEST_P(NoisePropsSmoothKind, SecondDerivativeIsContinuousAcrossFaces_GradientDifferences) {
  NoiseParams p;
  p.kind = GetParam();
  p.seed = 18;
  const NoiseField field(p);
  const double h = 1e-3;
  double max_jump = 0.0, sum_sq = 0.0;
  int samples = 0;
  for (const LineSpec& l : random_lines(300, 6)) {
    const DerivFn g = [&](double s) {
      const auto q = l.at(s);
      const NoiseGradient d = field.eval_gradient(q[0], q[1], q[2]);
      return double(l.axis == 0 ? d.dx : (l.axis == 1 ? d.dy : d.dz));
    };
    max_jump = std::max(max_jump, jump_by_gradient_differences(g, h));
    // RMS of f'' along the line (both cells), by central differences of the gradient.
    for (int i = 1; i < 100; ++i) {
      const double s = -1.0 + i / 50.0;
      const double d2 = (g(s + h) - g(s - h)) / (2.0 * h);
      sum_sq += d2 * d2;
      ++samples;
    }
  }
  const double rms = std::sqrt(sum_sq / samples);
  std::printf("%s (gradient differences, h = %g): RMS f'' %.4f, max jump %.3g (%.3g of RMS)\n",
              std::string(to_string(p.kind)).c_str(), h, rms, max_jump, max_jump / rms);
  EXPECT_GT(rms, 0.5);
  EXPECT_LE(max_jump, 1e-3 * rms);

  // The same estimator flags the C1 reference (derivative by exact calculus, in double).
  double min_ratio = 1e300;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const DerivFn gc = [seed](double s) {
      const double c = std::floor(s), t = s - c;
      Rng a(seed * 131 + uint64_t(int64_t(c) + 1000)), b(seed * 131 + uint64_t(int64_t(c) + 1001));
      const double v0 = a.uniform(-1, 1), v1 = b.uniform(-1, 1);
      return 6.0 * t * (1.0 - t) * (v1 - v0);
    };
    // RMS f'' of smoothstep interpolation of uniform(-1,1) values is about 2.8.
    min_ratio = std::min(min_ratio, jump_by_gradient_differences(gc, h) / 2.8);
  }
  EXPECT_GT(min_ratio, 1e-2);
}

// Analytic gradients against central differences (h = 1e-3, double input).
//
// eval() rounds to float and its own float arithmetic adds up to ~1.8e-6 (the Horner form of
// the fade loses a few bits as t -> 1), so a central difference of eval() at h = 1e-3 has a
// rounding floor of ~1.4e-4 RMS per gradient, independent of the gradient's size: above both
// an absolute 1e-4 and 1e-4 * RMS|grad| for fields of frequency 1 (RMS|grad| ~ 1.2-1.3).
// Hence two checks:
//  A. eval_gradient()'s gradient against central differences of eval_gradient()'s value
//     (computed in double, rounded once): RMS|err| <= 1e-4 absolute, for every case; and
//     that value equals eval() to 4e-6 (max), which ties the gradient to eval().
//  B. Against central differences of eval() itself: RMS|err| <= 1e-4 * RMS|grad| where the
//     rounding floor allows it (fields with RMS|grad| >= 2, here frequency 2.3); printed for
//     every case.
// The fBm cases use a first-octave frequency of 0.25 so that the truncation error of the
// difference (h^2/6 times the third derivative, which grows with the cube of the frequency)
// stays small for the top octave (frequency 2^3 * 0.25 = 2).
struct GradCase {
  std::string name;
  NoiseParams params;
  bool check_eval_differences;  // B applies
};
void PrintTo(const GradCase& c, std::ostream* os) { *os << c.name; }

std::vector<GradCase> grad_cases() {
  std::vector<GradCase> out;
  for (Kind k : {Kind::Value, Kind::Gradient}) {
    const std::string kn = k == Kind::Value ? "Value" : "Gradient";
    NoiseParams p;
    p.kind = k;
    p.seed = 9;
    out.push_back({kn, p, false});
    p.frequency = 2.3;
    out.push_back({kn + "Freq2p3", p, true});
    p.frequency = 0.25;
    p.fractal = Fractal::Fbm;
    p.octaves = 4;
    out.push_back({kn + "Fbm4", p, false});
    p.period = {5, 7, 16};
    out.push_back({kn + "Fbm4Periodic", p, false});
  }
  return out;
}

class NoisePropsGradient : public ::testing::TestWithParam<GradCase> {};

TEST_P(NoisePropsGradient, AnalyticGradientMatchesCentralDifferences) {
  const GradCase& c = GetParam();
  const NoiseField field(c.params);
  const double h = 1e-3;
  Rng rng(77);
  double err_a2 = 0.0, err_b2 = 0.0, grad2 = 0.0, max_err_a = 0.0, value_err = 0.0;
  const int n = 20000;
  auto value = [&](double x, double y, double z) { return double(field.eval_gradient(x, y, z).value); };
  auto evalf = [&](double x, double y, double z) { return double(field.eval(x, y, z)); };
  for (int i = 0; i < n; ++i) {
    const double x = rng.uniform(-300, 300), y = rng.uniform(-300, 300), z = rng.uniform(-300, 300);
    const NoiseGradient g = field.eval_gradient(x, y, z);
    const double an[3] = {g.dx, g.dy, g.dz};
    const double cd_a[3] = {(value(x + h, y, z) - value(x - h, y, z)) / (2 * h),
                            (value(x, y + h, z) - value(x, y - h, z)) / (2 * h),
                            (value(x, y, z + h) - value(x, y, z - h)) / (2 * h)};
    const double cd_b[3] = {(evalf(x + h, y, z) - evalf(x - h, y, z)) / (2 * h),
                            (evalf(x, y + h, z) - evalf(x, y - h, z)) / (2 * h),
                            (evalf(x, y, z + h) - evalf(x, y, z - h)) / (2 * h)};
    double ea = 0.0;
    for (int a = 0; a < 3; ++a) {
      ea += (an[a] - cd_a[a]) * (an[a] - cd_a[a]);
      err_b2 += (an[a] - cd_b[a]) * (an[a] - cd_b[a]);
      grad2 += an[a] * an[a];
    }
    err_a2 += ea;
    max_err_a = std::max(max_err_a, std::sqrt(ea));
    value_err = std::max(value_err, std::fabs(double(g.value) - evalf(x, y, z)));
  }
  const double rms_a = std::sqrt(err_a2 / n), rms_b = std::sqrt(err_b2 / n), rms_grad = std::sqrt(grad2 / n);
  std::printf("gradient %-20s RMS|grad| %.4f | A: RMS err %.3g (max %.3g) | B (eval): RMS err %.3g "
              "= %.3g of RMS|grad| | max |value - eval| %.3g\n",
              c.name.c_str(), rms_grad, rms_a, max_err_a, rms_b, rms_b / rms_grad, value_err);
  RecordProperty("rms_err_value_differences", std::to_string(rms_a));
  RecordProperty("rms_err_eval_differences", std::to_string(rms_b));
  EXPECT_GT(rms_grad, 0.1);
  EXPECT_LE(rms_a, 1e-4);
  EXPECT_LE(value_err, 4e-6);
  if (c.check_eval_differences) {
    EXPECT_LE(rms_b, 1e-4 * rms_grad);
  }
}

INSTANTIATE_TEST_SUITE_P(ValueAndGradient, NoisePropsGradient, ::testing::ValuesIn(grad_cases()),
                         [](const ::testing::TestParamInfo<GradCase>& param_info) { return param_info.param.name; });

INSTANTIATE_TEST_SUITE_P(ValueAndGradient, NoisePropsSmoothKind,
                         ::testing::Values(Kind::Value, Kind::Gradient),
                         [](const ::testing::TestParamInfo<Kind>& param_info) {
                           return std::string(param_info.param == Kind::Value ? "Value" : "Gradient");
                         });

TEST(NoisePropsGradientErrors, UnsupportedFieldsThrowLogicError) {
  NoiseParams w;
  w.kind = Kind::Wavelet;
  EXPECT_THROW(NoiseField(w).eval_gradient(0.1, 0.2, 0.3), std::logic_error);
  NoiseParams a;
  a.kind = Kind::Gradient;
  a.time = 0.5;
  EXPECT_THROW(NoiseField(a).eval_gradient(0.1, 0.2, 0.3), std::logic_error);
}

}  // namespace
}  // namespace nimbus::noise
