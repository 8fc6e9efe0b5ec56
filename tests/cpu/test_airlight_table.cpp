// The classic table method (Sun et al. eqs. 7-12 with an N x N bilinear F table): its error
// shrinks with N where the formula is well conditioned and stays large near gamma = pi, where
// A0 ~ e^{Tsv} multiplies the difference of two nearly equal lookups. This documents the
// problem the stable evaluation solves.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "nimbus/render/media/airlight.hpp"

namespace {

using nimbus::render::AirlightQuery;
using nimbus::render::FTable;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

double max_table_error(const FTable& t) {  // over a 97 x 97 grid off the table's nodes
  double worst = 0.0;
  for (int i = 0; i <= 96; ++i)
    for (int j = 0; j <= 96; ++j) {
      const double u = 10.0 * (i + 0.37) / 97.0, v = 0.5 * kPi * (j + 0.61) / 97.0;
      worst = std::max(worst, std::abs(t.lookup(u, v) - nimbus::render::F_exact(u, v)));
    }
  return worst;
}

TEST(AirlightTable, HoldsExactFAtItsNodesInRowMajorOrder) {
  const FTable t(16);
  EXPECT_EQ(t.size(), 16);
  for (int j : {0, 5, 15})
    for (int i : {0, 7, 15}) {
      const double u = 10.0 * i / 15, v = 0.5 * kPi * j / 15;
      EXPECT_NEAR(t.data()[j * 16 + i], nimbus::render::F_exact(u, v), 1e-7) << i << " " << j;
      EXPECT_NEAR(t.lookup(u, v), nimbus::render::F_exact(u, v), 1e-12);
    }
  // Clamped outside [0, 10] x [0, pi/2].
  EXPECT_DOUBLE_EQ(t.lookup(25.0, 0.3), t.lookup(10.0, 0.3));
  EXPECT_DOUBLE_EQ(t.lookup(-1.0, 0.3), t.lookup(0.0, 0.3));
  EXPECT_TRUE(std::isnan(t.lookup(std::nan(""), 0.3)));
  // Eq. 11 as printed divides by Tsv sin(gamma): beta = 0 gives NaN, which the method reports.
  EXPECT_TRUE(std::isnan(nimbus::render::airlight_table({0.0, 1.0, 1.0, 1.0, 1.0}, t)));
  EXPECT_THROW(FTable(15), std::invalid_argument);
  EXPECT_THROW(FTable(1025), std::invalid_argument);
}

TEST(AirlightTable, TableErrorShrinksWithSize) {
  // Bilinear error is largest where dF/du is singular (u -> 0, v -> pi/2).
  double previous = 1.0;
  for (int n : {16, 32, 64, 128, 256}) {
    const double err = max_table_error(FTable(n));
    EXPECT_LT(err, previous) << n;
    previous = err;
  }
  EXPECT_LT(previous, 0.02);
}

TEST(AirlightTable, AirlightErrorShrinksWithSizeWhereWellConditioned) {
  // gamma in [0.5, 2], Tsv in [0.3, 3]: the method's intended use.
  double previous = 1.0;
  for (int n : {16, 64, 256}) {
    const FTable table(n);
    double worst = 0.0;
    for (double gamma : {0.5, 1.0, 1.5, 2.0})
      for (double Tsv : {0.3, 1.0, 3.0})
        for (double Dvp : {0.5, 4.0, kInf}) {
          const AirlightQuery q{0.1, 10.0, Tsv / 0.1, Dvp / 0.1, gamma};
          const double err =
              std::abs(nimbus::render::airlight_table(q, table) / nimbus::render::airlight_quadrature(q) - 1.0);
          worst = std::max(worst, err);
        }
    EXPECT_LT(worst, previous) << n;
    previous = worst;
  }
  EXPECT_LT(previous, 0.03);
}

TEST(AirlightTable, FailsNearPiWhereTheStableEvaluationDoesNot) {
  // Light behind the viewer with a thick medium: the table is off by far more than 50 %, the
  // stable evaluation is not.
  const FTable table(64);
  for (double gamma : {3.0, 3.13}) {
    const AirlightQuery q{1.0, 1.0, 10.0, kInf, gamma};
    const double ref = nimbus::render::airlight_quadrature(q);
    EXPECT_GT(std::abs(nimbus::render::airlight_table(q, table) / ref - 1.0), 0.5) << gamma;
    EXPECT_LT(std::abs(nimbus::render::airlight_stable(q) / ref - 1.0), 1e-3) << gamma;
  }
  // And beyond the table's u range (A1 = Tsv sin gamma > 10) the clamped lookup is wrong too.
  const AirlightQuery wide{1.0, 1.0, 40.0, kInf, 1.0};
  EXPECT_GT(std::abs(nimbus::render::airlight_table(wide, FTable(256)) / nimbus::render::airlight_quadrature(wide) - 1.0),
            0.5);
}

}  // namespace
