// The float32 stable airlight (shaders/lib/airlight.glsl compiled as C++) against the double
// reference: the target grid (<= 1e-3), anisotropic phases, segments away from the eye,
// the limits, additivity, and finite non-negative output for degenerate and huge inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
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

// The target region, log-spaced: gamma in [1e-3, pi - 1e-3] (dense toward both ends),
// beta Dsv in [1e-3, 50], beta Dvp in [1e-3, 1e4] and infinity; beta cycles through three
// values so that the lengths themselves vary.
std::vector<AirlightQuery> target_grid(int n_gamma, int n_depth) {
  std::vector<double> gammas;
  for (int i = 0; i < n_gamma; ++i) {
    const double f = double(i) / (n_gamma - 1);
    gammas.push_back(1e-3 * std::pow(1.5e3, f));
    gammas.push_back(kPi - 1e-3 * std::pow(1.5e3, f));
  }
  const double betas[3] = {1.0, 1e-3, 37.0};
  std::vector<AirlightQuery> out;
  int k = 0;
  for (double gamma : gammas)
    for (int i = 0; i < n_depth; ++i)
      for (int j = 0; j <= n_depth; ++j) {
        const double beta = betas[k++ % 3];
        const double Tsv = 1e-3 * std::pow(5e4, double(i) / (n_depth - 1));
        const double Tvp = j == n_depth ? kInf : 1e-3 * std::pow(1e7, double(j) / (n_depth - 1));
        out.push_back({beta, 3.0, Tsv / beta, Tvp / beta, gamma});
      }
  return out;
}

std::string describe(const AirlightQuery& q) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "beta=%g I0=%g Dsv=%g Dvp=%g gamma=%.9g (Tsv=%g Tvp=%g)", q.beta, q.I0, q.Dsv, q.Dvp,
                q.gamma, q.beta * q.Dsv, q.beta * q.Dvp);
  return buf;
}

TEST(AirlightStable, MeetsTheTargetOverTheDenseGrid) {
  double worst = 0.0;
  std::string where;
  const auto grid = target_grid(24, 16);
  for (const AirlightQuery& q : grid) {
    const double ref = nimbus::render::airlight_quadrature(q), got = nimbus::render::airlight_stable(q);
    const double err = std::abs(got / ref - 1.0);
    if (!(err <= worst)) {
      worst = err;
      where = describe(q);
    }
  }
  std::printf("stable vs quadrature: %zu queries, max relative error %.3g at %s\n", grid.size(), worst, where.c_str());
  EXPECT_LE(worst, 1e-3) << where;
}

SegmentQuery segment(double sigma_t, double Dsv, double gamma, double x0, double x1, Phase phase) {
  SegmentQuery q;
  q.sigma_t = sigma_t;
  q.sigma_s = 0.8 * sigma_t;
  q.I0 = 2.0;
  q.Dsv = Dsv;
  q.cos_gamma = std::cos(gamma);
  q.sin_gamma = std::sin(gamma);
  q.x0 = x0;
  q.x1 = x1;
  q.phase = phase;
  return q;
}

TEST(AirlightStable, AnisotropicPhasesStayWithinTwoPerMille) {
  // No target in the issue; measured on this grid: <= 1.2e-4 (docs/airlight.md). The phases
  // cover the three panel layouts: no peak (g = 0.3, Rayleigh), forward and backward peaks.
  const Phase phases[] = {{PhaseKind::HenyeyGreenstein, 0.9},  {PhaseKind::HenyeyGreenstein, -0.5},
                          {PhaseKind::Schlick, 0.9},           {PhaseKind::Schlick, -0.5},
                          {PhaseKind::Rayleigh, 0.0},          {PhaseKind::HenyeyGreenstein, 0.3},
                          {PhaseKind::HenyeyGreenstein, 0.99}, {PhaseKind::HenyeyGreenstein, -0.9}};
  for (const Phase& phase : phases) {
    double worst = 0.0;
    std::string where;
    for (const AirlightQuery& a : target_grid(10, 9)) {
      const SegmentQuery q = segment(a.beta, a.Dsv, a.gamma, 0.0, a.Dvp, phase);
      const double ref = nimbus::render::segment_airlight_quadrature(q);
      const double err = std::abs(nimbus::render::segment_airlight_stable(q) / ref - 1.0);
      if (!(err <= worst)) {
        worst = err;
        where = describe(a);
      }
    }
    std::printf("%s: max relative error %.3g at %s\n", nimbus::render::to_string(phase).c_str(), worst, where.c_str());
    EXPECT_LE(worst, 2e-3) << nimbus::render::to_string(phase) << " " << where;
  }
}

TEST(AirlightStable, SegmentsAwayFromTheEye) {
  double worst = 0.0;
  for (const Phase& phase : {Phase{}, Phase{PhaseKind::HenyeyGreenstein, 0.7}})
    for (double gamma : {1e-3, 0.1, 1.0, 2.5, kPi - 1e-3})
      for (double Tsv : {1e-3, 0.3, 5.0, 40.0})
        for (double x0 : {0.1, 0.9, 1.0, 3.0})      // in units of Dsv
          for (double len : {1e-3, 0.5, 4.0, kInf}) {  // in units of Dsv
            const double sigma_t = 0.2, Dsv = Tsv / sigma_t;
            const SegmentQuery q = segment(sigma_t, Dsv, gamma, x0 * Dsv, (x0 + len) * Dsv, phase);
            const double ref = nimbus::render::segment_airlight_quadrature(q);
            if (ref < 1e-36) continue;  // below float's range: e^{-sigma_t (x0 + d0)} underflows
            const double err = std::abs(nimbus::render::segment_airlight_stable(q) / ref - 1.0);
            worst = std::max(worst, err);
            EXPECT_LE(err, 1e-3) << gamma << " " << Tsv << " " << x0 << " " << len << " "
                                 << nimbus::render::to_string(phase);
          }
  std::printf("segments away from the eye: max relative error %.3g\n", worst);
}

TEST(AirlightStable, ShortSegmentsKeepTheirRelativeAccuracy) {
  // Segments from 1e-6 Dsv long, anywhere on the ray: panel lengths and node positions are
  // formed as offsets from the segment start, never as differences of nearly equal numbers.
  // The ends are rounded to float first (the shader receives floats: a segment of 1e-6 Dsv at
  // x0 = Dsv is known only to 6 % in float), so that this measures the evaluation itself.
  double worst = 0.0;
  for (const Phase& phase : {Phase{}, Phase{PhaseKind::HenyeyGreenstein, 0.9}, Phase{PhaseKind::Schlick, -0.7}})
    for (double gamma : {1e-3, 0.5, 2.0, kPi - 1e-3})
      for (double Tsv : {1e-3, 1.0, 50.0})
        for (double x0 : {0.0, 0.5, 1.0, 2.0})  // in units of Dsv
          for (double len : {1e-6, 1e-4, 1e-2}) {
            const double sigma_t = 0.5, Dsv = Tsv / sigma_t;
            const SegmentQuery q = segment(sigma_t, Dsv, gamma, double(float(x0 * Dsv)),
                                           double(float((x0 + len) * Dsv)), phase);
            const double ref = nimbus::render::segment_airlight_quadrature(q);
            if (ref < 1e-36) continue;  // below float's range
            const double err = std::abs(nimbus::render::segment_airlight_stable(q) / ref - 1.0);
            worst = std::max(worst, err);
            EXPECT_LE(err, 1e-3) << gamma << " " << Tsv << " " << x0 << " " << len << " "
                                 << nimbus::render::to_string(phase);
          }
  std::printf("short segments: max relative error %.3g\n", worst);
}

TEST(AirlightStable, SegmentsAddUp) {
  for (double gamma : {0.05, 1.3, 3.0})
    for (double cut : {0.3, 9.99, 25.0}) {
      const SegmentQuery whole = segment(0.05, 10.0, gamma, 0.0, kInf, Phase{PhaseKind::HenyeyGreenstein, 0.6});
      SegmentQuery first = whole, second = whole;
      first.x1 = cut;
      second.x0 = cut;
      const double parts = nimbus::render::segment_airlight_stable(first) + nimbus::render::segment_airlight_stable(second);
      EXPECT_NEAR(parts / nimbus::render::segment_airlight_stable(whole), 1.0, 2e-4) << gamma << " " << cut;
    }
}

TEST(AirlightStable, ThinMediumLimitAndNoMedium) {
  for (double gamma : {1e-3, 0.7, 2.0, kPi - 1e-3})
    for (double Dvp : {0.2, 3.0, kInf}) {
      const AirlightQuery q{1e-7, 2.0, 1.0, Dvp, gamma};
      const double c = std::cos(gamma), s = std::sin(gamma);
      const double angle = std::isinf(Dvp) ? kPi - gamma : std::atan((Dvp - c) / s) + kPi / 2 - gamma;
      const double limit = q.beta * q.I0 * angle / (4.0 * kPi * s);
      EXPECT_NEAR(nimbus::render::airlight_stable(q) / limit, 1.0, 1e-4) << gamma << " " << Dvp;
    }
  EXPECT_EQ(nimbus::render::airlight_stable({0.0, 2.0, 1.0, kInf, 1.0}), 0.0);
}

TEST(AirlightStable, ContinuousAtTheEndsOfTheTargetRange) {
  // gamma = pi exactly (light straight behind) and the infinite ray as limits.
  for (double Tsv : {1e-3, 1.0, 50.0}) {
    const double ref = nimbus::render::airlight_quadrature({1.0, 1.0, Tsv, kInf, kPi});
    EXPECT_NEAR(nimbus::render::airlight_stable({1.0, 1.0, Tsv, kInf, kPi}) / ref, 1.0, 1e-3) << Tsv;
    const double far = nimbus::render::airlight_stable({1.0, 1.0, Tsv, 1e4, 2.0});
    EXPECT_NEAR(far / nimbus::render::airlight_stable({1.0, 1.0, Tsv, kInf, 2.0}), 1.0, 1e-5) << Tsv;
  }
  // gamma = 0 with the ray ending before the light: finite and right.
  const AirlightQuery before{0.3, 1.0, 10.0, 4.0, 0.0};
  EXPECT_NEAR(nimbus::render::airlight_stable(before) / nimbus::render::airlight_quadrature(before), 1.0, 1e-3);
}

TEST(AirlightStable, FiniteAndNonNegativeEverywhereElse) {
  const double huge = 1e30, tiny = 1e-30;
  const double values_beta[] = {0.0, tiny, 1e-3, 1.0, 1e3, huge};
  const double values_I0[] = {0.0, 1.0, huge};
  const double values_D[] = {0.0, tiny, 1.0, huge};
  const double values_Dvp[] = {0.0, tiny, 1.0, huge, kInf};
  const double values_gamma[] = {0.0, 1e-9, 1.0, kPi - 1e-9, kPi};
  int n = 0;
  for (double beta : values_beta)
    for (double I0 : values_I0)
      for (double Dsv : values_D)
        for (double Dvp : values_Dvp)
          for (double gamma : values_gamma) {
            const AirlightQuery q{beta, I0, Dsv, Dvp, gamma};
            const double v = nimbus::render::airlight_stable(q);
            EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << describe(q) << " -> " << v;
            ++n;
          }
  EXPECT_EQ(n, 6 * 3 * 4 * 5 * 5);
  // The segment form with anisotropic phases, segments starting anywhere.
  for (double x0 : {0.0, 1.0, huge})
    for (double gamma : {0.0, kPi})
      for (const Phase& phase : {Phase{PhaseKind::HenyeyGreenstein, 0.99}, Phase{PhaseKind::Schlick, -0.99}}) {
        const double v = nimbus::render::segment_airlight_stable(segment(1.0, 1.0, gamma, x0, x0 + 2.0, phase));
        EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << x0 << " " << gamma;
      }
}

TEST(AirlightStable, SunSegmentIsTheClosedForm) {
  const Phase hg{PhaseKind::HenyeyGreenstein, 0.5};
  for (double sigma_t : {0.0, 1e-9, 1e-3, 0.5, 3.0})
    for (double x0 : {0.0, 2.0})
      for (double x1 : {2.5, 10.0, kInf}) {
        const double cos_theta = 0.3, E = 4.0, sigma_s = 0.25;
        const double p = nimbus::render::phase_value(hg, cos_theta);
        const double span = sigma_t == 0.0 ? x1 - x0
                                           : (std::exp(-sigma_t * x0) - (std::isinf(x1) ? 0.0 : std::exp(-sigma_t * x1))) / sigma_t;
        const double expected = sigma_s * p * E * span;
        const double got = nimbus::render::sun_segment_airlight_stable(sigma_t, sigma_s, E, cos_theta, x0, x1, hg);
        if (std::isinf(expected)) {
          EXPECT_TRUE(std::isfinite(got) && got > 1e37);
        } else {
          EXPECT_NEAR(got / expected, 1.0, 1e-5) << sigma_t << " " << x0 << " " << x1;
        }
      }
}

}  // namespace
