// Ray marching the airlight (N midpoint samples of Sun et al. eq. 5): second-order convergence
// to the reference, and the cut-off of an infinite ray.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "nimbus/render/media/airlight.hpp"

namespace {

using nimbus::render::AirlightQuery;
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(AirlightRaymarch, ConvergesToTheReferenceAtSecondOrder) {
  for (const AirlightQuery& q : {AirlightQuery{0.5, 2.0, 2.0, 4.0, 1.0}, AirlightQuery{0.05, 2.0, 20.0, 60.0, 2.5}}) {
    const double ref = nimbus::render::airlight_quadrature(q);
    double previous = 0.0;
    for (int n : {50, 100, 200, 400}) {
      const double err = std::abs(nimbus::render::airlight_raymarch(q, n) - ref);
      if (previous > 0.0) {
        EXPECT_GT(previous / err, 3.6) << n;  // midpoint rule: error ~ 1/N^2, ratio 4
        EXPECT_LT(previous / err, 4.4) << n;
      }
      previous = err;
    }
    EXPECT_LT(previous / ref, 1e-4);
  }
}

TEST(AirlightRaymarch, PhaseFunctionsConvergeToTheSegmentReference) {
  for (const nimbus::render::Phase& phase :
       {nimbus::render::Phase{nimbus::render::PhaseKind::HenyeyGreenstein, 0.6},
        nimbus::render::Phase{nimbus::render::PhaseKind::Rayleigh, 0.0}}) {
    const AirlightQuery q{0.5, 2.0, 2.0, 4.0, 1.0};
    const double ref = nimbus::render::segment_airlight_quadrature(nimbus::render::to_segment(q, phase));
    EXPECT_NEAR(nimbus::render::airlight_raymarch(q, 4000, phase) / ref, 1.0, 1e-6) << nimbus::render::to_string(phase);
  }
}

TEST(AirlightRaymarch, InfiniteRayIsCutWhereTheRestIsNegligible) {
  for (double gamma : {0.4, 1.5, 3.0}) {
    const AirlightQuery q{1.0, 1.0, 1.0, kInf, gamma};
    const double ref = nimbus::render::airlight_quadrature(q);
    EXPECT_NEAR(nimbus::render::airlight_raymarch(q, 200000) / ref, 1.0, 1e-6) << gamma;
  }
  EXPECT_EQ(nimbus::render::airlight_raymarch({0.0, 1.0, 1.0, kInf, 1.0}, 10), 0.0);
  EXPECT_THROW(nimbus::render::airlight_raymarch({1.0, 1.0, 1.0, 1.0, 1.0}, 0), std::invalid_argument);
}

TEST(AirlightRaymarch, MissesTheNearLightPeakWithFewSamples) {
  // The ray passes 1 mm from the light: 20 uniform samples cannot see the peak, the stable
  // evaluation can. This is why the renderer's ray marcher needs many steps near lamps.
  const AirlightQuery q{0.02, 1.0, 10.0, 20.0, 1e-4};
  const double ref = nimbus::render::airlight_quadrature(q);
  EXPECT_GT(std::abs(nimbus::render::airlight_raymarch(q, 20) / ref - 1.0), 0.5);
  EXPECT_LT(std::abs(nimbus::render::airlight_stable(q) / ref - 1.0), 1e-3);
}

}  // namespace
