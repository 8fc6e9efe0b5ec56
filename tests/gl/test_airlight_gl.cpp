// The airlight GLSL functions evaluated on an OpenGL context (shaders/airlight_eval.comp.glsl):
// the shader's own float numerics against the double reference, and against the same source
// compiled as C++. Skipped, with the reason, where no OpenGL 4.5 context can be had.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/shafts/airlight_gl.hpp"
#include "nimbus/render/gl/context.hpp"
#include "support/run_nimbus.hpp"

namespace {

using nimbus::render::AirlightMethod;
using nimbus::render::AirlightQuery;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<AirlightQuery> target_grid() {  // as in test_airlight_stable.cpp, a little coarser
  std::vector<AirlightQuery> out;
  const double betas[3] = {1.0, 1e-3, 37.0};
  int k = 0;
  for (int i = 0; i < 20; ++i) {
    const double f = i / 19.0;
    for (double gamma : {1e-3 * std::pow(1.5e3, f), kPi - 1e-3 * std::pow(1.5e3, f)})
      for (int a = 0; a < 14; ++a)
        for (int b = 0; b <= 14; ++b) {
          const double beta = betas[k++ % 3];
          const double Tsv = 1e-3 * std::pow(5e4, a / 13.0);
          const double Tvp = b == 14 ? kInf : 1e-3 * std::pow(1e7, b / 13.0);
          out.push_back({beta, 3.0, Tsv / beta, Tvp / beta, gamma});
        }
  }
  return out;
}

// Skips the test, naming the reason, when no GL context can be made.
#define REQUIRE_GL()                                                      \
  try {                                                                   \
    nimbus::render::GlContext::create_headless();                         \
  } catch (const nimbus::render::GlUnavailable& e) {                      \
    GTEST_SKIP() << "no OpenGL 4.5 context: " << e.what();                \
  }

TEST(AirlightGl, StableShaderMeetsTheTargetOnTheGpuContext) {
  REQUIRE_GL();
  const auto grid = target_grid();
  const auto gl = nimbus::render::evaluate_airlight_gl(grid, {AirlightMethod::Stable, 0});
  const auto cpu = nimbus::render::evaluate_airlight(grid, {AirlightMethod::Stable, 0});
  ASSERT_EQ(gl.size(), grid.size());
  double worst = 0.0, worst_cpu = 0.0;
  size_t at = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    const double ref = nimbus::render::airlight_quadrature(grid[i]);
    const double err = std::abs(gl[i] / ref - 1.0);
    if (!(err <= worst)) {
      worst = err;
      at = i;
    }
    worst_cpu = std::max(worst_cpu, std::abs(gl[i] / cpu[i] - 1.0));
  }
  const AirlightQuery& q = grid[at];
  std::printf("GL stable vs quadrature: %zu queries, max relative error %.3g at beta=%g Dsv=%g Dvp=%g gamma=%.9g; "
              "GL vs the same code on the CPU: %.3g\n",
              grid.size(), worst, q.beta, q.Dsv, q.Dvp, q.gamma, worst_cpu);
  EXPECT_LE(worst, 1e-3);
  EXPECT_LE(worst_cpu, 1e-4);  // same source, the driver's exp/log/sqrt instead of libm's
}

TEST(AirlightGl, AnisotropicPhasesOnTheGpuContext) {
  REQUIRE_GL();
  std::vector<AirlightQuery> grid;  // every third query of the target grid
  const auto all = target_grid();
  for (size_t i = 0; i < all.size(); i += 3) grid.push_back(all[i]);
  const nimbus::render::Phase phases[] = {{nimbus::render::PhaseKind::HenyeyGreenstein, 0.9},
                                          {nimbus::render::PhaseKind::Schlick, -0.5},
                                          {nimbus::render::PhaseKind::Rayleigh, 0.0},
                                          {nimbus::render::PhaseKind::HenyeyGreenstein, -0.9}};
  for (const auto& phase : phases) {
    const auto gl = nimbus::render::evaluate_airlight_gl(grid, {AirlightMethod::Stable, 0}, phase);
    const auto ref = nimbus::render::evaluate_airlight(grid, {AirlightMethod::Quadrature, 0}, phase);
    double worst = 0.0;
    for (size_t i = 0; i < grid.size(); ++i) worst = std::max(worst, std::abs(gl[i] / ref[i] - 1.0));
    std::printf("GL stable %s: %zu queries, max relative error %.3g\n", nimbus::render::to_string(phase).c_str(),
                grid.size(), worst);
    EXPECT_LE(worst, 2e-3) << nimbus::render::to_string(phase);
  }
}

TEST(AirlightGl, FiniteAndNonNegativeForDegenerateAndHugeInputs) {
  REQUIRE_GL();
  std::vector<AirlightQuery> qs;
  for (double beta : {0.0, 1e-30, 1.0, 1e30})
    for (double Dsv : {0.0, 1e-30, 1.0, 1e30})
      for (double Dvp : {0.0, 1.0, 1e30, kInf})
        for (double gamma : {0.0, 1e-9, 1.0, kPi - 1e-9, kPi}) qs.push_back({beta, 1e30, Dsv, Dvp, gamma});
  const auto gl = nimbus::render::evaluate_airlight_gl(qs, {AirlightMethod::Stable, 0});
  for (size_t i = 0; i < qs.size(); ++i)
    EXPECT_TRUE(std::isfinite(gl[i]) && gl[i] >= 0.0) << qs[i].beta << " " << qs[i].Dsv << " " << qs[i].Dvp << " "
                                                      << qs[i].gamma << " -> " << gl[i];
}

TEST(AirlightGl, TableAndRaymarchShadersMatchTheirCpuVersions) {
  REQUIRE_GL();
  std::vector<AirlightQuery> qs;
  for (double gamma : {0.3, 1.0, 2.0, 2.8})
    for (double Tsv : {0.2, 1.0, 4.0})
      for (double Dvp : {3.0, 30.0, kInf}) qs.push_back({0.1, 10.0, Tsv / 0.1, Dvp, gamma});
  const AirlightMethod table{AirlightMethod::Table, 64}, march{AirlightMethod::RayMarch, 400};
  const auto gl_table = nimbus::render::evaluate_airlight_gl(qs, table);
  const auto cpu_table = nimbus::render::evaluate_airlight(qs, table);
  const auto gl_march = nimbus::render::evaluate_airlight_gl(qs, march);
  const auto cpu_march = nimbus::render::evaluate_airlight(qs, march);
  for (size_t i = 0; i < qs.size(); ++i) {
    // The table in float: close to the double table where nothing cancels (gamma <= 2); at
    // gamma = 2.8 the difference of two float lookups is amplified by A0 (measured up to 0.8 %).
    EXPECT_NEAR(gl_table[i] / cpu_table[i], 1.0, qs[i].gamma <= 2.0 ? 1e-4 : 2e-2) << i;
    EXPECT_NEAR(gl_march[i] / cpu_march[i], 1.0, 1e-4) << i;
  }
}

TEST(AirlightGl, CommandLineDeviceGlAgreesWithCpu) {
  REQUIRE_GL();
  const auto r = nimbus::test::run_command("printf '0.04,100,30,55,0.6\\n1,1,10,inf,3.13\\n' | " +
                                           std::string(NIMBUS_BINARY) + " airlight --method stable --device gl");
  ASSERT_EQ(r.code, 0) << r.output;
  double a = 0, b = 0;
  ASSERT_EQ(std::sscanf(r.output.c_str(), "%lf %lf", &a, &b), 2) << r.output;
  EXPECT_NEAR(a / nimbus::render::airlight_quadrature({0.04, 100, 30, 55, 0.6}), 1.0, 1e-3);
  EXPECT_NEAR(b / nimbus::render::airlight_quadrature({1, 1, 10, kInf, 3.13}), 1.0, 1e-3);
}

}  // namespace
