// The double-precision references: adaptive quadrature of Sun et al. eq. 5 and of its segment
// form against brute-force Simpson in x, the beta -> 0 closed form, F(u, v), continuity at the
// limits, segment additivity (Biri et al. eq. 12) and input validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/media/airlight.hpp"

namespace {

using nimbus::render::AirlightQuery;
using nimbus::render::Phase;
using nimbus::render::PhaseKind;
using nimbus::render::SegmentQuery;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

SegmentQuery segment(double sigma_t, double Dsv, double gamma, double x0, double x1, Phase phase = {}) {
  SegmentQuery q;
  q.sigma_t = sigma_t;
  q.sigma_s = 0.7 * sigma_t + 0.01;
  q.I0 = 5.0;
  q.Dsv = Dsv;
  q.cos_gamma = std::cos(gamma);
  q.sin_gamma = std::sin(gamma);
  q.x0 = x0;
  q.x1 = x1;
  q.phase = phase;
  return q;
}

// Brute force: composite Simpson in x of the segment integrand (thesis eq. 33), on panels graded
// geometrically around the light's foot point a (width h = Dsv sin gamma), 1000 intervals each.
double brute_force(const SegmentQuery& q) {
  const double a = q.Dsv * q.cos_gamma, h = q.Dsv * q.sin_gamma;
  auto f = [&](double x) {
    const double along = x - a, d2 = along * along + h * h, d = std::sqrt(d2);
    const double cos_theta = -along / d;  // dot(unit(point - light), -view)
    return q.sigma_s * nimbus::render::phase_value(q.phase, cos_theta) * q.I0 * std::exp(-q.sigma_t * (x + d)) / d2;
  };
  std::vector<double> cuts{q.x0, q.x1};
  for (int k = -3; k <= 16; ++k)
    for (double sign : {-1.0, 1.0}) {
      const double p = a + sign * h * std::ldexp(1.0, k);
      if (p > q.x0 && p < q.x1) cuts.push_back(p);
    }
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const int n = 1000;
    const double lo = cuts[i], step = (cuts[i + 1] - lo) / n;
    double s = f(lo) + f(cuts[i + 1]);
    for (int k = 1; k < n; ++k) s += f(lo + k * step) * (k % 2 ? 4.0 : 2.0);
    sum += s * step / 3.0;
  }
  return sum;
}

TEST(AirlightReference, QuadratureMatchesBruteForceSimpsonInX) {
  const Phase phases[] = {{}, {PhaseKind::HenyeyGreenstein, 0.9}, {PhaseKind::Rayleigh, 0.0}};
  int checked = 0;
  for (const Phase& phase : phases)
    for (double gamma : {1e-3, 0.05, 0.8, 2.0, 3.1, kPi - 1e-3})
      for (double Tsv : {0.02, 1.0, 20.0})
        for (double ratio : {0.3, 3.0, 40.0}) {  // Dvp / Dsv
          for (double x0_ratio : {0.0, 0.2}) {
            const double sigma_t = 0.5, Dsv = Tsv / sigma_t;
            const SegmentQuery q = segment(sigma_t, Dsv, gamma, x0_ratio * Dsv, ratio * Dsv, phase);
            const double ref = nimbus::render::segment_airlight_quadrature(q), bf = brute_force(q);
            EXPECT_NEAR(ref / bf, 1.0, 1e-8) << "gamma=" << gamma << " Tsv=" << Tsv << " ratio=" << ratio
                                             << " x0=" << q.x0 << " " << nimbus::render::to_string(phase);
            ++checked;
          }
        }
  EXPECT_EQ(checked, 324);
}

TEST(AirlightReference, SunsAirlightIsTheIsotropicSegmentFromTheEye) {
  const AirlightQuery q{0.04, 100.0, 30.0, 55.0, 0.6};
  SegmentQuery s = segment(0.04, 30.0, 0.6, 0.0, 55.0);
  s.sigma_s = 0.04;
  s.I0 = 100.0;
  EXPECT_DOUBLE_EQ(nimbus::render::airlight_quadrature(q), nimbus::render::segment_airlight_quadrature(s));
  // And eq. 5 itself by brute force.
  EXPECT_NEAR(nimbus::render::airlight_quadrature(q) / brute_force(s), 1.0, 1e-8);
}

// beta -> 0: La = beta I0 (atan((Dvp - Dsv cos g)/(Dsv sin g)) + pi/2 - g) / (4 pi Dsv sin g).
double thin_limit(const AirlightQuery& q) {
  const double c = std::cos(q.gamma), s = std::sin(q.gamma);
  const double angle = std::isinf(q.Dvp) ? kPi - q.gamma : std::atan((q.Dvp - q.Dsv * c) / (q.Dsv * s)) + kPi / 2 - q.gamma;
  return q.beta * q.I0 * angle / (4.0 * kPi * q.Dsv * s);
}

TEST(AirlightReference, ThinMediumLimitIsTheClosedForm) {
  for (double gamma : {1e-3, 0.3, 1.5, 2.9, kPi - 1e-3})
    for (double Dvp : {0.5, 2.0, 50.0, kInf}) {
      const AirlightQuery q{1e-9, 2.0, 1.0, Dvp, gamma};
      EXPECT_NEAR(nimbus::render::airlight_quadrature(q) / thin_limit(q), 1.0, 1e-7) << gamma << " " << Dvp;
    }
  // beta = 0 exactly: no scattering, no airlight.
  EXPECT_EQ(nimbus::render::airlight_quadrature({0.0, 2.0, 1.0, kInf, 1.0}), 0.0);
}

TEST(AirlightReference, InfiniteRayIsTheLimitOfLongOnes) {
  for (double gamma : {0.01, 1.0, 3.0}) {
    const double inf = nimbus::render::airlight_quadrature({0.5, 1.0, 4.0, kInf, gamma});
    const double far = nimbus::render::airlight_quadrature({0.5, 1.0, 4.0, 200.0, gamma});
    EXPECT_NEAR(far / inf, 1.0, 1e-12) << gamma;
    EXPECT_LT(nimbus::render::airlight_quadrature({0.5, 1.0, 4.0, 20.0, gamma}), inf);
  }
  // Without extinction the tail decays only like 1/Dvp.
  const AirlightQuery thin{1e-12, 1.0, 1.0, kInf, 1.0};
  const AirlightQuery long_ray{1e-12, 1.0, 1.0, 1e6, 1.0};
  EXPECT_NEAR(nimbus::render::airlight_quadrature(long_ray) / nimbus::render::airlight_quadrature(thin), 1.0, 1e-6);
}

TEST(AirlightReference, FiniteAndContinuousAtGammaZeroAndPi) {
  // Light behind the viewer: gamma = pi exactly is the limit of gamma -> pi.
  for (double Tsv : {0.01, 1.0, 50.0}) {
    const double at_pi = nimbus::render::airlight_quadrature({1.0, 1.0, Tsv, kInf, kPi});
    const double near_pi = nimbus::render::airlight_quadrature({1.0, 1.0, Tsv, kInf, kPi - 1e-7});
    ASSERT_TRUE(std::isfinite(at_pi) && at_pi > 0.0) << Tsv;
    EXPECT_NEAR(near_pi / at_pi, 1.0, 1e-9) << Tsv;
    // gamma = pi: int_0^inf beta I0 e^{-beta (Dsv + 2x)} / (4 pi (Dsv + x)^2) dx, by Simpson in 1/(Dsv + x).
    const int n = 20000;
    double sum = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double y = (1.0 / Tsv) * k / n;  // y = 1/(Dsv + x), from 0 (x = inf) to 1/Dsv
      const double f = y > 0.0 ? std::exp(-(2.0 / y - Tsv)) : 0.0;
      sum += f * ((k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0));
    }
    const double simpson = sum * (1.0 / Tsv / n) / 3.0 / (4.0 * kPi);
    EXPECT_NEAR(at_pi / simpson, 1.0, 1e-8) << Tsv;
  }
  // Light ahead: gamma = 0 with the ray ending before the light is finite (a closed form),
  // continuous with gamma -> 0; passing through the light it is infinite.
  const double before = nimbus::render::airlight_quadrature({0.3, 1.0, 10.0, 4.0, 0.0});
  const double expected = 0.3 / (4.0 * kPi) * std::exp(-3.0) * (1.0 / 6.0 - 1.0 / 10.0);
  EXPECT_NEAR(before / expected, 1.0, 1e-12);
  EXPECT_NEAR(nimbus::render::airlight_quadrature({0.3, 1.0, 10.0, 4.0, 1e-6}) / before, 1.0, 1e-9);
  EXPECT_TRUE(std::isinf(nimbus::render::airlight_quadrature({0.3, 1.0, 10.0, 20.0, 0.0})));
  const double grazing = nimbus::render::airlight_quadrature({0.3, 1.0, 10.0, 20.0, 1e-6});
  EXPECT_TRUE(std::isfinite(grazing) && grazing > 100.0);  // about sigma_s e^{-Tsv} / (4 h), h = 1e-5
}

TEST(AirlightReference, SegmentsAddUp) {
  // Biri et al. eq. 12: the airlight of [0, b] is that of [0, a] plus that of [a, b].
  for (const Phase& phase : {Phase{}, Phase{PhaseKind::HenyeyGreenstein, 0.8}, Phase{PhaseKind::Schlick, -0.4}})
    for (double gamma : {0.02, 1.2, 3.0})
      for (double a : {0.5, 9.9, 10.0, 30.0}) {
        const SegmentQuery whole = segment(0.1, 10.0, gamma, 0.0, kInf, phase);
        SegmentQuery first = whole, second = whole;
        first.x1 = a;
        second.x0 = a;
        const double w = nimbus::render::segment_airlight_quadrature(whole);
        const double parts =
            nimbus::render::segment_airlight_quadrature(first) + nimbus::render::segment_airlight_quadrature(second);
        EXPECT_NEAR(parts / w, 1.0, 1e-10) << gamma << " " << a << " " << nimbus::render::to_string(phase);
      }
}

TEST(AirlightReference, FactorisedFormWithExactFMatchesAwayFromPi) {
  // Sun eqs. 7-11 with F evaluated exactly: the same number where nothing cancels.
  for (double gamma : {0.3, 1.0, 2.0})
    for (double Tsv : {0.1, 1.0, 5.0}) {
      const AirlightQuery q{0.5, 3.0, Tsv / 0.5, 7.0, gamma};
      const double Tvp = q.beta * q.Dvp, c = std::cos(gamma), s = std::sin(gamma);
      const double A0 = q.beta * q.beta * q.I0 * std::exp(-Tsv * c) / (2.0 * kPi * Tsv * s);
      const double A1 = Tsv * s, v1 = kPi / 4 + 0.5 * std::atan((Tvp - Tsv * c) / (Tsv * s));
      const double La = A0 * (nimbus::render::F_exact(A1, v1) - nimbus::render::F_exact(A1, gamma / 2));
      EXPECT_NEAR(La / nimbus::render::airlight_quadrature(q), 1.0, 1e-9) << gamma << " " << Tsv;
    }
}

TEST(AirlightReference, FIsExactAtItsLimitsAndAgreesWithSimpson) {
  EXPECT_DOUBLE_EQ(nimbus::render::F_exact(0.0, 1.2), 1.2);
  EXPECT_EQ(nimbus::render::F_exact(3.0, 0.0), 0.0);
  for (double u : {0.1, 1.0, 10.0})
    for (double v : {0.2, 1.0, kPi / 2}) {
      const int n = 200000;
      double sum = 0.0;
      for (int k = 0; k <= n; ++k) {
        const double xi = v * k / n;
        const double f = xi >= kPi / 2 ? 0.0 : std::exp(-u * std::tan(xi));
        sum += f * ((k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0));
      }
      EXPECT_NEAR(nimbus::render::F_exact(u, v), sum * v / n / 3.0, 1e-9) << u << " " << v;
    }
  EXPECT_THROW(nimbus::render::F_exact(-1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(nimbus::render::F_exact(1.0, 2.0), std::invalid_argument);
}

TEST(AirlightReference, BadQueriesNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad {
    AirlightQuery q;
    const char* field;
  };
  const Bad bad[] = {{{-1.0, 1, 1, 1, 1}, "beta"}, {{nan, 1, 1, 1, 1}, "beta"},  {{1, -1, 1, 1, 1}, "I0"},
                     {{1, 1, nan, 1, 1}, "Dsv"},   {{1, 1, kInf, 1, 1}, "Dsv"},  {{1, 1, 1, -2, 1}, "Dvp"},
                     {{1, 1, 1, nan, 1}, "Dvp"},   {{1, 1, 1, 1, -0.1}, "gamma"}, {{1, 1, 1, 1, 3.2}, "gamma"},
                     {{1, 1, 1, 1, nan}, "gamma"}};
  for (const Bad& b : bad) {
    try {
      nimbus::render::airlight_quadrature(b.q);
      ADD_FAILURE() << "accepted bad " << b.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(b.field, 0), 0u) << e.what();
    }
  }
  SegmentQuery s = segment(0.1, 1.0, 1.0, 2.0, 1.0);  // x1 < x0
  EXPECT_THROW(nimbus::render::segment_airlight_quadrature(s), std::invalid_argument);
}

}  // namespace
