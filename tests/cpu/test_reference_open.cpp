// The reference's airlight of a point light where nothing occludes, against independent
// values: the beta -> 0 closed form of Sun et al.'s integral, brute-force composite Simpson
// with 1e6 intervals for a thick anisotropic medium, and airlight.hpp's segment quadrature
// (a separate implementation in the scattering-angle variable).
#include <gtest/gtest.h>

#include <cmath>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"

namespace nr = nimbus::render;

namespace {

// A point light, and optionally a black wall at z = -30 (so view rays end at a known distance
// and see no surface radiance).
nr::Scene open_scene(double sigma_t, double albedo, nr::Phase phase, bool wall) {
  nr::Scene s;
  s.name = "test-open";
  s.medium.extinction_per_m = sigma_t;
  s.medium.albedo = albedo;
  s.medium.phase = phase;
  s.lamps.push_back(nr::bulb_light({1.0, 2.0, -4.0}, glm::dvec3{100.0, 50.0, 25.0}, 0.05));
  if (wall) s.boxes.push_back({{-500, -500, -31}, {500, 500, -30}, {{0.0, 0.0, 0.0}}});
  s.camera.eye = {0.0, 0.0, 10.0};
  s.camera.look_at = {0.0, 0.0, 0.0};
  return s;
}

struct Geometry {
  double dsv, gamma, d_end;  // light distance, angle between ray and light, ray length (or inf)
};
Geometry geometry(const nr::Scene& s, const glm::dvec3& dir, bool wall) {
  const glm::dvec3 v = s.lamps[0].position_m - s.camera.eye;
  Geometry g;
  g.dsv = glm::length(v);
  g.gamma = std::acos(glm::dot(v, dir) / g.dsv);
  g.d_end = wall ? (s.camera.eye.z + 30.0) / -dir.z : INFINITY;
  return g;
}

// Sun et al.'s integral in the limit beta -> 0 (isotropic phase, I0 = 1):
// La = sigma_s (atan((D - Dsv cos g) / (Dsv sin g)) + pi/2 - g) / (4 pi Dsv sin g).
double thin_limit(double sigma_s, const Geometry& g) {
  const double s = std::sin(g.gamma), c = std::cos(g.gamma);
  const double at = std::isinf(g.d_end) ? M_PI / 2 : std::atan((g.d_end - g.dsv * c) / (g.dsv * s));
  return sigma_s * (at + M_PI / 2 - g.gamma) / (4.0 * M_PI * g.dsv * s);
}

// Composite Simpson over [0, D] with n intervals of sigma_s p(theta) e^(-sigma_t (x + d)) / d^2.
double simpson(const nr::Scene& s, const glm::dvec3& dir, double D, long n) {
  const glm::dvec3 o = s.camera.eye, L = s.lamps[0].position_m;
  const double st = s.medium.extinction_per_m, ss = s.medium.scattering_per_m();
  auto f = [&](double x) {
    const glm::dvec3 p = o + x * dir;
    const double d = glm::length(p - L);
    const double cos_theta = glm::dot((p - L) / d, -dir);
    return ss * nr::phase_value(s.medium.phase, cos_theta) * std::exp(-st * (x + d)) / (d * d);
  };
  const double h = D / n;
  double sum = f(0.0) + f(D);
  for (long i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(i * h);
  return sum * h / 3.0;
}

}  // namespace

TEST(ReferenceOpen, ThinMediumMatchesTheBetaToZeroClosedForm) {
  nr::ReferenceSettings settings;
  settings.rel_tol = 1e-9;
  for (const bool wall : {true, false}) {
    const nr::Scene s = open_scene(1e-8, 1.0, nr::Phase{}, wall);
    for (const glm::dvec3 target : {glm::dvec3{0, 0, 0}, glm::dvec3{1.0, 2.2, -4.0}, glm::dvec3{-3, 1, 8},
                                    glm::dvec3{1.0, 2.0, -3.0}}) {
      const glm::dvec3 dir = glm::normalize(target - s.camera.eye);
      const Geometry g = geometry(s, dir, wall);
      const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, dir, settings);
      const double expect = thin_limit(s.medium.scattering_per_m(), g);
      // The limit is exact to first order in beta (x + d): relative error ~ 1e-8 * 100 m.
      EXPECT_NEAR(r.radiance.x / 100.0, expect, 1e-5 * expect) << "wall " << wall << " gamma " << g.gamma;
      EXPECT_NEAR(r.radiance.z / r.radiance.x, 0.25, 1e-12);
      EXPECT_EQ(r.alpha, 1.0);  // thin fog is still fog: nothing shows through
    }
  }
}

TEST(ReferenceOpen, ThickAnisotropicMediumMatchesBruteForceSimpson) {
  nr::ReferenceSettings settings;
  settings.rel_tol = 1e-9;
  const nr::Scene s = open_scene(0.1, 0.8, nr::Phase{nr::PhaseKind::HenyeyGreenstein, 0.5}, true);
  // Rays passing the light at 0.2 m, 1 m and 5 m (peak widths), and one away from it.
  for (const glm::dvec3 target : {glm::dvec3{1.0, 2.2, -4.0}, glm::dvec3{1.0, 3.0, -4.0},
                                  glm::dvec3{6.0, 2.0, -4.0}, glm::dvec3{-4, -2, 0}}) {
    const glm::dvec3 dir = glm::normalize(target - s.camera.eye);
    const Geometry g = geometry(s, dir, true);
    const double expect = simpson(s, dir, g.d_end, 1000000);
    const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, dir, settings);
    EXPECT_NEAR(r.radiance.y / 50.0, expect, 1e-8 * expect) << target.x << "," << target.y;
    EXPECT_EQ(r.alpha, 1.0);
  }
}

TEST(ReferenceOpen, VacuumIsTransparentAndDark) {
  const nr::Scene s = open_scene(0.0, 1.0, nr::Phase{}, false);
  const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, {0, 0, -1});
  EXPECT_EQ(r.alpha, 0.0);
  EXPECT_EQ(r.radiance, glm::dvec3(0.0));
  // The bulb seen directly: radiance I0 / (pi r^2), unattenuated in vacuum.
  const glm::dvec3 to_bulb = s.lamps[0].position_m - s.camera.eye;
  const nr::ReferenceSample b = nr::reference_ray(s, s.camera.eye, to_bulb);
  EXPECT_EQ(b.alpha, 1.0);
  EXPECT_NEAR(b.radiance.x, 100.0 / (M_PI * 0.05 * 0.05), 1e-9);
}

TEST(ReferenceOpen, BulbIsAttenuatedAndAddsTheAirlightInFrontOfIt) {
  // Absorbing-only fog (albedo 0): only the bulb's own attenuated radiance.
  const nr::Scene s = open_scene(0.07, 0.0, nr::Phase{}, false);
  const glm::dvec3 to_bulb = s.lamps[0].position_m - s.camera.eye;
  const double t = glm::length(to_bulb) - 0.05;
  const nr::ReferenceSample b = nr::reference_ray(s, s.camera.eye, to_bulb);
  EXPECT_NEAR(b.radiance.y, 50.0 / (M_PI * 0.05 * 0.05) * std::exp(-0.07 * t), 1e-9 * b.radiance.y);
  // Scattering fog: the same plus the airlight over [0, t], which stays finite.
  const nr::Scene f = open_scene(0.07, 1.0, nr::Phase{}, false);
  nr::ReferenceSettings settings;
  settings.rel_tol = 1e-9;
  const nr::ReferenceSample bf = nr::reference_ray(f, f.camera.eye, to_bulb, settings);
  const double air = (bf.radiance.y - b.radiance.y) / 50.0;
  EXPECT_NEAR(air, simpson(f, glm::normalize(to_bulb), t, 1000000), 1e-6 * air);
}

TEST(ReferenceOpen, AgreesWithTheSegmentAirlightQuadrature) {
  nr::ReferenceSettings settings;
  settings.rel_tol = 1e-10;
  for (const nr::Phase phase : {nr::Phase{nr::PhaseKind::Schlick, -0.4}, nr::Phase{nr::PhaseKind::Rayleigh, 0.0},
                                nr::Phase{nr::PhaseKind::HenyeyGreenstein, 0.8}}) {
    for (const bool wall : {true, false}) {
      const nr::Scene s = open_scene(0.04, 0.7, phase, wall);
      for (const glm::dvec3 target : {glm::dvec3{1.0, 2.5, -4.0}, glm::dvec3{-2, 1, 4}, glm::dvec3{0, 0, 30}}) {
        const glm::dvec3 dir = glm::normalize(target - s.camera.eye);
        const Geometry g = geometry(s, dir, wall);
        if (wall && !(dir.z < 0.0)) continue;
        nr::SegmentQuery q;
        q.sigma_t = s.medium.extinction_per_m;
        q.sigma_s = s.medium.scattering_per_m();
        q.I0 = 1.0;
        q.Dsv = g.dsv;
        q.cos_gamma = std::cos(g.gamma);
        q.sin_gamma = std::sin(g.gamma);
        q.x0 = 0.0;
        q.x1 = g.d_end;
        q.phase = phase;
        const double expect = nr::segment_airlight_quadrature(q);
        const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, dir, settings);
        EXPECT_NEAR(r.radiance.x / 100.0, expect, 1e-8 * expect) << nr::to_string(phase) << " wall " << wall;
      }
    }
  }
}
