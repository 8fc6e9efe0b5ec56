// Visibility in the reference: the sun's airlight in closed form with and without an
// occluder, a point light's airlight with a shadowed segment known exactly, and surfaces in
// and out of a sphere's shadow.
#include <gtest/gtest.h>

#include <cmath>

#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"

namespace nr = nimbus::render;

namespace {

nr::Scene base_scene(double sigma_t, double albedo, nr::Phase phase) {
  nr::Scene s;
  s.name = "test-shadow";
  s.medium.extinction_per_m = sigma_t;
  s.medium.albedo = albedo;
  s.medium.phase = phase;
  s.camera.eye = {0.0, 1.0, 0.0};
  s.camera.look_at = {1.0, 1.0, 0.0};
  return s;
}

// int_a^b e^(-s x) dx
double exp_integral(double s, double a, double b) {
  return (std::exp(-s * a) - (std::isinf(b) ? 0.0 : std::exp(-s * b))) / s;
}

}  // namespace

TEST(ReferenceShadow, UnoccludedSunAirlightIsClosedForm) {
  nr::Scene s = base_scene(0.05, 0.9, nr::Phase{nr::PhaseKind::HenyeyGreenstein, 0.4});
  s.ground = nr::GroundPlane{0.0, {{0.0, 0.0, 0.0}}};  // black: the airlight alone
  s.sun = nr::sun_light({0.3, 0.8, -0.5}, {3.0, 2.0, 1.0});
  const glm::dvec3 u = glm::normalize(s.sun->direction_to_sun);
  const double ss = s.medium.scattering_per_m(), st = s.medium.extinction_per_m;
  // A ray reaching the ground at t, and one escaping to infinity.
  for (const glm::dvec3 d : {glm::normalize(glm::dvec3{1.0, -0.05, 0.3}), glm::normalize(glm::dvec3{-0.2, 0.1, 1.0})}) {
    const double t = d.y < 0 ? 1.0 / -d.y : INFINITY;
    const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, d);
    const double expect = ss * nr::phase_value(s.medium.phase, glm::dot(u, d)) * 3.0 * exp_integral(st, 0.0, t);
    EXPECT_NEAR(r.radiance.x, expect, 1e-13 * expect) << t;
    EXPECT_NEAR(r.radiance.z * 3.0, r.radiance.x, 1e-13 * expect);
    EXPECT_EQ(r.alpha, 1.0);
  }
}

TEST(ReferenceShadow, BoxOverTheRayRemovesExactlyItsSegmentOfSunAirlight) {
  nr::Scene s = base_scene(0.05, 1.0, nr::Phase{nr::PhaseKind::Rayleigh, 0.0});
  s.sun = nr::sun_light({0.0, 1.0, 0.0}, {2.0, 2.0, 2.0});  // overhead
  s.boxes.push_back({{4.0, 5.0, -1.0}, {7.0, 6.0, 1.0}, {}});
  s.boxes.push_back({{-10.0, 0.0, -10.0}, {-9.0, 10.0, 10.0}, {{0.0, 0.0, 0.0}}});  // behind, black
  s.boxes.push_back({{20.0, -10.0, -10.0}, {21.0, 10.0, 10.0}, {{0.0, 0.0, 0.0}}});  // ray ends at 20 m
  const double ss = s.medium.scattering_per_m(), st = s.medium.extinction_per_m;
  const double p = nr::phase_value(s.medium.phase, 0.0);
  const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, {1, 0, 0});
  const double lit = exp_integral(st, 0.0, 4.0) + exp_integral(st, 7.0, 20.0);
  EXPECT_NEAR(r.radiance.x, ss * p * 2.0 * lit, 1e-8 * ss * p * 2.0 * lit);
}

TEST(ReferenceShadow, PlateUnderAPointLightShadowsAKnownSegment) {
  // Light at (0, 5, 0); view ray along +x at height 0 from x = -20 to a black wall at x = 40.
  // A plate at 2.5 <= y <= 2.6 over a <= x <= b < 0 (z in [-1, 1]) shadows the points of the
  // ray whose segment to the light crosses it (x (1 - y / 5) in [a, b]): x in [a / 0.48, 2b],
  // before the light, where HG g > 0 scatters most toward the eye.
  nr::Scene s = base_scene(0.03, 1.0, nr::Phase{nr::PhaseKind::HenyeyGreenstein, 0.3});
  s.lamps.push_back(nr::bulb_light({0.0, 5.0, 0.0}, glm::dvec3{80.0}, 0.1));
  const double a = -6.0, b = -3.0;
  s.boxes.push_back({{a, 2.5, -1.0}, {b, 2.6, 1.0}, {}});
  s.boxes.push_back({{40.0, -10.0, -10.0}, {41.0, 10.0, 10.0}, {{0.0, 0.0, 0.0}}});
  s.camera.eye = {-20.0, 0.0, 0.0};
  s.camera.look_at = {0.0, 0.0, 0.0};
  const double st = s.medium.extinction_per_m, ss = s.medium.scattering_per_m();
  // Independent integral over the lit part in the angle phi seen from the light (x = h tan
  // phi, dx / d^2 = dphi / h), composite Simpson with 2e5 intervals per piece.
  const double h = 5.0;
  auto piece = [&](double x0, double x1) {
    auto f = [&](double phi) {
      const double x = h * std::tan(phi), d = h / std::cos(phi);
      return ss * nr::phase_value(s.medium.phase, -x / d) * std::exp(-st * (x + 20.0 + d)) / h;
    };
    const double p0 = std::atan(x0 / h), p1 = std::atan(x1 / h);
    const long n = 200000;
    const double dp = (p1 - p0) / n;
    double sum = f(p0) + f(p1);
    for (long i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(p0 + i * dp);
    return sum * dp / 3.0;
  };
  const double lit = piece(-20.0, a / 0.48) + piece(2.0 * b, 40.0);
  const double dark = piece(a / 0.48, 2.0 * b);
  nr::ReferenceSettings settings;
  settings.rel_tol = 1e-10;
  const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, {1, 0, 0}, settings);
  EXPECT_NEAR(r.radiance.x / 80.0, lit, 1e-8 * lit);
  // The plate's segment is a sizeable part of the whole: the test would see it missing.
  EXPECT_GT(dark, 0.1 * lit);
}

TEST(ReferenceShadow, GroundInASpheresShadowGetsNoDirectLight) {
  // Absorbing fog only (no airlight), so the radiance is the attenuated surface term.
  nr::Scene s = base_scene(0.04, 0.0, nr::Phase{});
  s.ground = nr::GroundPlane{0.0, {{0.5, 0.4, 0.3}}};
  s.spheres.push_back({{0.0, 2.0, 0.0}, 0.5, {}});
  s.lamps.push_back(nr::bulb_light({0.0, 4.0, 0.0}, glm::dvec3{60.0}, 0.05));
  s.camera.eye = {6.0, 3.0, 0.0};
  s.camera.look_at = {0.0, 0.0, 0.0};
  const double st = s.medium.extinction_per_m;
  for (const glm::dvec3 ground : {glm::dvec3{0.0, 0.0, 0.0}, glm::dvec3{0.3, 0.0, -0.4}, glm::dvec3{3.0, 0.0, 1.0}}) {
    const glm::dvec3 d = ground - s.camera.eye;
    const double t = glm::length(d);
    const nr::ReferenceSample r = nr::reference_ray(s, s.camera.eye, d);
    EXPECT_EQ(r.alpha, 1.0);
    // The sphere's shadow on the ground is the disc of radius 4 tan(asin(0.5 / 2)) = 1.033 m.
    if (glm::length(ground) < 1.0) {
      EXPECT_EQ(r.radiance, glm::dvec3(0.0)) << ground.x;
    } else {
      const glm::dvec3 to_light = s.lamps[0].position_m - ground;
      const double dist = glm::length(to_light), cos_i = to_light.y / dist;
      const double e = 0.5 / M_PI * 60.0 * cos_i * std::exp(-st * dist) / (dist * dist) * std::exp(-st * t);
      EXPECT_NEAR(r.radiance.x, e, 1e-12 * e);
      EXPECT_NEAR(r.radiance.z / r.radiance.x, 0.6, 1e-12);
    }
  }
}
