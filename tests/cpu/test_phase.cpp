// Phase functions (thesis eqs. 13-17) and the clouds' dual lobe: normalisation, limits, symmetry,
// the Schlick approximation's closeness to Henyey-Greenstein, the float shader version, their text
// form, and which kinds the fog and the clouds take.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/media/medium.hpp"

namespace {

using nimbus::render::Phase;
using nimbus::render::PhaseKind;
using nimbus::render::phase_value;

// Integral over the sphere of f(cos theta): 2 pi * int_{-1}^{1} f(mu) dmu, composite Simpson on
// a grid graded toward mu = +-1 (mu = sin(pi/2 s)), fine enough for the g = 0.9 peak.
template <class F>
double sphere_integral(F f) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double s = -1.0 + 2.0 * i / n;
    const double mu = std::sin(0.5 * std::numbers::pi * s);
    const double dmu_ds = 0.5 * std::numbers::pi * std::cos(0.5 * std::numbers::pi * s);
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * f(mu) * dmu_ds;
  }
  return 2.0 * std::numbers::pi * sum * (2.0 / n) / 3.0;
}

double mean_cosine(const Phase& p) {
  return sphere_integral([&](double mu) { return mu * phase_value(p, mu); });
}

TEST(Phase, EveryKindIsNormalisedOverTheSphere) {
  const Phase phases[] = {{PhaseKind::Isotropic, 0.0},        {PhaseKind::HenyeyGreenstein, 0.9},
                          {PhaseKind::HenyeyGreenstein, -0.5}, {PhaseKind::HenyeyGreenstein, 0.3},
                          {PhaseKind::Schlick, 0.9},           {PhaseKind::Schlick, -0.5},
                          {PhaseKind::Rayleigh, 0.0},          nimbus::render::dual_lobe_phase(0.9, -0.5, 0.3),
                          nimbus::render::kCloudPhase};
  for (const Phase& p : phases) {
    const double total = sphere_integral([&](double mu) { return phase_value(p, mu); });
    EXPECT_NEAR(total, 1.0, 1e-6) << nimbus::render::to_string(p);
  }
}

TEST(Phase, HenyeyGreensteinMeanCosineIsG) {
  for (double g : {-0.5, 0.3, 0.9}) EXPECT_NEAR(mean_cosine({PhaseKind::HenyeyGreenstein, g}), g, 1e-6) << g;
}

TEST(Phase, DualLobeIsItsLobesWeightedAndItsMeanCosineTheirs) {
  for (const Phase& d : {nimbus::render::dual_lobe_phase(0.7, -0.25, 0.8), nimbus::render::dual_lobe_phase(-0.6, 0.95, 0.1)}) {
    const Phase f{PhaseKind::HenyeyGreenstein, d.g}, b{PhaseKind::HenyeyGreenstein, d.g_back};
    for (double mu = -1.0; mu <= 1.0; mu += 0.0625)
      EXPECT_NEAR(phase_value(d, mu), d.forward_weight * phase_value(f, mu) + (1.0 - d.forward_weight) * phase_value(b, mu),
                  1e-12 * phase_value(d, mu));
    EXPECT_NEAR(mean_cosine(d), d.forward_weight * d.g + (1.0 - d.forward_weight) * d.g_back, 1e-6);
  }
}

// Clouds take sums of Henyey-Greenstein lobes in one form: isotropic and hg:G as dual lobes are
// the same function; Schlick and Rayleigh are refused, naming the phase.
TEST(Phase, CloudsTakeHenyeyGreensteinLobesAsOneDualForm) {
  using nimbus::render::as_dual_lobes;
  for (const Phase& p : {Phase{}, Phase{PhaseKind::HenyeyGreenstein, 0.9}, Phase{PhaseKind::HenyeyGreenstein, -0.4},
                         nimbus::render::kCloudPhase}) {
    const Phase d = as_dual_lobes(p);
    EXPECT_EQ(d.kind, PhaseKind::DualHenyeyGreenstein);
    for (double mu = -1.0; mu <= 1.0; mu += 0.0625)
      EXPECT_NEAR(phase_value(d, mu), phase_value(p, mu), 1e-12 * phase_value(p, mu)) << nimbus::render::to_string(p);
  }
  for (const char* text : {"schlick:0.3", "rayleigh"}) {
    const Phase p = nimbus::render::parse_phase(text);
    EXPECT_THROW(as_dual_lobes(p), std::invalid_argument) << text;
    nimbus::render::CloudOptics o;
    o.phase = p;
    try {
      nimbus::render::validate(o);
      ADD_FAILURE() << "cloud optics took " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
    try {
      nimbus::render::parse_cloud_phase(text);
      ADD_FAILURE() << "parse_cloud_phase took " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("cloud phase '" + std::string(text) + "'"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(nimbus::render::parse_cloud_phase("dual:0.7,-0.25,0.8"), nimbus::render::kCloudPhase);
}

// The fog's shaders and tables take one lobe: a dual lobe in the medium is refused, naming it.
TEST(Phase, TheFogTakesOneLobe) {
  nimbus::render::Medium m;
  m.phase = nimbus::render::kCloudPhase;
  try {
    nimbus::render::validate(m);
    ADD_FAILURE() << "the fog took a dual lobe";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dual:0.7,-0.25,0.8"), std::string::npos) << e.what();
  }
  EXPECT_THROW(nimbus::render::phase_code(PhaseKind::DualHenyeyGreenstein), std::invalid_argument);
  for (const char* text : {"isotropic", "hg:0.5", "schlick:-0.3", "rayleigh"}) {
    m.phase = nimbus::render::parse_phase(text);
    EXPECT_NO_THROW(nimbus::render::validate(m)) << text;
  }
}

TEST(Phase, HenyeyGreensteinWithGZeroIsIsotropic) {
  for (double mu = -1.0; mu <= 1.0; mu += 0.125)
    EXPECT_DOUBLE_EQ(phase_value({PhaseKind::HenyeyGreenstein, 0.0}, mu), 1.0 / (4.0 * std::numbers::pi));
  EXPECT_DOUBLE_EQ(phase_value({PhaseKind::Schlick, 0.0}, 0.3), 1.0 / (4.0 * std::numbers::pi));
}

TEST(Phase, ForwardMeansThetaZeroForPositiveG) {
  for (PhaseKind k : {PhaseKind::HenyeyGreenstein, PhaseKind::Schlick}) {
    EXPECT_GT(phase_value({k, 0.6}, 1.0), phase_value({k, 0.6}, -1.0));
    EXPECT_LT(phase_value({k, -0.6}, 1.0), phase_value({k, -0.6}, -1.0));
  }
  // HG peak value (1 + g) / (4 pi (1 - g)^2).
  EXPECT_NEAR(phase_value({PhaseKind::HenyeyGreenstein, 0.9}, 1.0), 1.9 / (4.0 * std::numbers::pi * 0.01), 1e-9);
}

TEST(Phase, SchlickApproximatesHenyeyGreensteinForModerateG) {
  // Measured: L1 distance over the sphere 0.023 (g = 0.3) and 0.057 (|g| = 0.5); mean cosine
  // 0.313 and 0.532 for g = 0.3 and 0.5.
  EXPECT_DOUBLE_EQ(nimbus::render::schlick_k(0.5), 1.55 * 0.5 - 0.55 * 0.125);
  for (double g : {0.3, 0.5, -0.5}) {
    const Phase hg{PhaseKind::HenyeyGreenstein, g}, sc{PhaseKind::Schlick, g};
    const double l1 = sphere_integral([&](double mu) { return std::abs(phase_value(hg, mu) - phase_value(sc, mu)); });
    EXPECT_LT(l1, 0.06) << g;
    EXPECT_NEAR(mean_cosine(sc), g, 0.035) << g;
  }
}

TEST(Phase, SchlickStaysValidWhereEq16GivesKAboveOne) {
  // k(0.97) = 1.0015 by eq. 16; the phase keeps k inside (-1, 1) and stays positive, normalised.
  EXPECT_GT(nimbus::render::schlick_k(0.97), 1.0);
  const Phase p{PhaseKind::Schlick, 0.97};
  for (double mu : {-1.0, 0.0, 1.0}) EXPECT_GT(phase_value(p, mu), 0.0);
  EXPECT_NEAR(sphere_integral([&](double mu) { return phase_value(p, mu); }), 1.0, 1e-4);
}

TEST(Phase, RayleighIsSymmetricForwardAndBack) {
  const Phase r{PhaseKind::Rayleigh, 0.0};
  for (double mu = 0.0; mu <= 1.0; mu += 0.1) EXPECT_DOUBLE_EQ(phase_value(r, mu), phase_value(r, -mu));
  EXPECT_NEAR(phase_value(r, 1.0), 2.0 * phase_value(r, 0.0), 1e-15);
  EXPECT_NEAR(mean_cosine(r), 0.0, 1e-12);
}

TEST(Phase, ShaderVersionAgreesWithTheDoubleReference) {
  const Phase phases[] = {{PhaseKind::Isotropic, 0.0}, {PhaseKind::HenyeyGreenstein, 0.9},
                          {PhaseKind::HenyeyGreenstein, -0.5}, {PhaseKind::Schlick, 0.7},
                          {PhaseKind::Schlick, -0.5}, {PhaseKind::Rayleigh, 0.0}};
  for (const Phase& p : phases)
    for (double mu = -1.0; mu <= 1.0; mu += 1.0 / 64.0) {
      const double ref = phase_value(p, mu), got = nimbus::render::phase_value_float(p, mu);
      EXPECT_NEAR(got / ref, 1.0, 2e-5) << nimbus::render::to_string(p) << " mu=" << mu;
    }
}

TEST(Phase, TextFormRoundTripsAndRejectsMalformedText) {
  for (const char* text : {"isotropic", "hg:0.9", "hg:-0.5", "schlick:0.25", "rayleigh", "dual:0.7,-0.25,0.8", "dual:-0.1,0.5,1"})
    EXPECT_EQ(nimbus::render::to_string(nimbus::render::parse_phase(text)), text);
  const Phase p = nimbus::render::parse_phase("hg:0.9");
  EXPECT_EQ(p.kind, PhaseKind::HenyeyGreenstein);
  EXPECT_DOUBLE_EQ(p.g, 0.9);
  for (const char* bad : {"", "iso", "hg", "hg:", "hg:1", "hg:-1", "hg:0.5x", "schlick:nan", "mie:0.5", "rayleigh:0.1",
                          "dual:", "dual:0.7", "dual:0.7,-0.25", "dual:0.7,-0.25,0.8,1", "dual:1,0,0.5", "dual:0.5,-1,0.5",
                          "dual:0.5,0,1.5", "dual:0.5,0,-0.1", "dual:nan,0,1", "dual:0.5,x,1"}) {
    try {
      nimbus::render::parse_phase(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("phase '" + std::string(bad) + "'"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
