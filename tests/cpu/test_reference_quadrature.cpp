// The reference's Gauss-Kronrod quadrature: polynomial exactness of both rules (which checks
// every node and weight) and adaptive refinement of a sharp peak against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "nimbus/render/core/quadrature.hpp"

namespace nr = nimbus::render;

TEST(ReferenceQuadrature, KronrodExactToDegree23AndGaussToDegree13) {
  const double a = -0.3, b = 1.7;
  for (int k = 0; k <= 25; ++k) {
    const auto f = [k](double x) { return std::pow(x, k); };
    const double exact = (std::pow(b, k + 1) - std::pow(a, k + 1)) / (k + 1);
    const auto [kron, diff] = nr::gauss_kronrod15(f, a, b);
    if (k <= 23) {  // 3n + 1 = 22, and 23 by the rule's symmetry
      EXPECT_NEAR(kron, exact, 1e-14 * std::abs(exact)) << "degree " << k;
    } else {
      EXPECT_GT(std::abs(kron - exact), 1e-14 * std::abs(exact)) << "degree " << k;  // not exact beyond
    }
    // |K15 - G7| vanishes where the Gauss rule is exact too (degree <= 13), not beyond.
    if (k <= 13) {
      EXPECT_LT(diff, 1e-14 * std::abs(exact)) << "degree " << k;
    } else {
      EXPECT_GT(diff, 1e-12 * std::abs(exact)) << "degree " << k;
    }
  }
}

TEST(ReferenceQuadrature, AdaptiveResolvesANarrowPeak) {
  // Lorentzian of width h at x = 3 (the profile of a light passing close to a view ray).
  for (const double h : {1.0, 1e-2, 1e-4}) {
    const auto f = [h](double x) { return 1.0 / (h * h + (x - 3.0) * (x - 3.0)); };
    const double exact = (std::atan(7.0 / h) + std::atan(3.0 / h)) / h;
    const auto r = nr::integrate_adaptive(f, {{0.0, 3.0}, {3.0, 10.0}}, 1e-10);
    EXPECT_TRUE(r.converged);
    EXPECT_NEAR(r.value, exact, 1e-10 * exact) << h;
    EXPECT_LE(r.error, 1e-10 * exact);
  }
  // Pieces with a < b only; an empty list integrates to 0.
  const auto zero = nr::integrate_adaptive([](double) { return 1.0; }, {}, 1e-6);
  EXPECT_EQ(zero.value, 0.0);
  // A budget too small is reported, not hidden.
  const auto capped = nr::integrate_adaptive([](double x) { return std::sqrt(x); }, {{0.0, 1.0}}, 1e-15, 0.0, 4);
  EXPECT_FALSE(capped.converged);
  EXPECT_NEAR(capped.value, 2.0 / 3.0, 1e-3);
}
