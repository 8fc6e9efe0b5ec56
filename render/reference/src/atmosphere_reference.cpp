// Brute-force double-precision integration of the physical sky (atmosphere_reference.hpp).
#include "nimbus/render/reference/atmosphere_reference.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "nimbus/render/core/quadrature.hpp"

namespace nimbus::render {
namespace {

constexpr int kPsiDirections = 512;
constexpr int kPsiSteps = 128;
constexpr int kSunSteps = 48;  // midpoint steps of the sun's optical depth inside Psi_ms
constexpr int kViewSteps = 2000;
constexpr int kPsiNodes = 24;

// Optical depth along (h, mu) over [0, d]: each density profile integrated adaptively, then
// weighted by its coefficients per channel.
glm::dvec3 optical_depth(const Atmosphere& a, double h, double mu, double d) {
  if (!(d > 0.0)) return glm::dvec3(0.0);
  auto alt = [&](double t) { return shell_point(a, h, mu, 0.0, 0.0, t).altitude_m; };
  auto rayleigh = [&](double t) { return std::exp(-alt(t) / a.rayleigh_scale_height_m); };
  auto mie = [&](double t) { return std::exp(-alt(t) / a.mie_scale_height_m); };
  auto ozone = [&](double t) { return std::max(0.0, 1.0 - std::abs(alt(t) - a.ozone_centre_m) / a.ozone_half_width_m); };
  const double iR = integrate_adaptive(rayleigh, 0.0, d, {}, 1.0e-9, 1.0e-12).value;
  const double iM = integrate_adaptive(mie, 0.0, d, {}, 1.0e-9, 1.0e-12).value;
  const double iO = integrate_adaptive(ozone, 0.0, d, {}, 1.0e-9, 1.0e-12).value;
  return a.rayleigh_scattering_per_m * iR + glm::dvec3(a.mie_extinction_per_m * iM) + a.ozone_absorption_per_m * iO;
}

// The sun's transmittance by the midpoint rule in n steps (inside Psi_ms, where millions are needed).
glm::dvec3 sun_transmittance_midpoint(const Atmosphere& a, double h, double mu_s, int n) {
  const double vis = sun_visibility(a, h, mu_s);
  if (vis <= 0.0) return glm::dvec3(0.0);
  const double mu = std::max(mu_s, horizon_cos(a, h));
  const double d = distance_to_top(a, h, mu);
  glm::dvec3 tau(0.0);
  for (int k = 0; k < n; ++k) {
    const ShellPoint p = shell_point(a, h, mu, 0.0, 0.0, (k + 0.5) * d / n);
    tau += atmosphere_medium(a, p.altitude_m).extinction;
  }
  return glm::exp(-tau * (d / n)) * vis;
}

glm::dvec3 sun_transmittance_exact(const Atmosphere& a, double h, double mu_s) {
  const double vis = sun_visibility(a, h, mu_s);
  if (vis <= 0.0) return glm::dvec3(0.0);
  const double mu = std::max(mu_s, horizon_cos(a, h));
  return glm::exp(-optical_depth(a, h, mu, distance_to_top(a, h, mu))) * vis;
}

}  // namespace

glm::dvec3 reference_transmittance(const Atmosphere& a, double altitude_m, double mu) {
  if (ray_hits_ground(a, altitude_m, mu)) return glm::dvec3(0.0);
  return glm::exp(-optical_depth(a, altitude_m, mu, distance_to_top(a, altitude_m, mu)));
}

glm::dvec3 reference_multiple_scattering(const Atmosphere& a, double h, double mu_s) {
  const glm::dvec3 sun_dir{std::sqrt(std::max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0};
  std::vector<glm::dvec3> L(kPsiDirections), F(kPsiDirections);
  tbb::parallel_for(0, kPsiDirections, [&](int i) {
    const glm::dvec3 dir = fibonacci_sphere(i, kPsiDirections);
    const double mu = dir.y;
    const double nu = glm::dot(dir, sun_dir);
    const double end = distance_to_exit(a, h, mu);
    glm::dvec3 Li(0.0), Fi(0.0), T(1.0);
    for (int k = 0; k < kPsiSteps; ++k) {
      const double dt = end / kPsiSteps;
      const ShellPoint p = shell_point(a, h, mu, mu_s, nu, (k + 0.5) * dt);
      const AtmosphereMedium m = atmosphere_medium(a, p.altitude_m);
      const glm::dvec3 w = T * step_weight(m.extinction, dt);
      Li += w * m.scattering * sun_transmittance_midpoint(a, p.altitude_m, p.mu_s, kSunSteps) / (4.0 * M_PI);
      Fi += w * m.scattering;
      T *= glm::exp(-m.extinction * dt);
    }
    if (ray_hits_ground(a, h, mu)) {
      const ShellPoint g = shell_point(a, h, mu, mu_s, nu, end);
      Li += T * sun_transmittance_midpoint(a, 0.0, g.mu_s, kSunSteps) * (a.ground_albedo / M_PI) * std::max(g.mu_s, 0.0);
    }
    L[i] = Li;
    F[i] = Fi;
  });
  glm::dvec3 L2(0.0), fms(0.0);
  for (int i = 0; i < kPsiDirections; ++i) {
    L2 += L[i];
    fms += F[i];
  }
  L2 /= static_cast<double>(kPsiDirections);
  fms /= static_cast<double>(kPsiDirections);
  return L2 / (1.0 - fms);
}

AtmosphereRadiance reference_sky(const Atmosphere& a, const AtmosphereRay& ray) {
  const glm::dvec3 sun = glm::normalize(ray.direction_to_sun), dir = glm::normalize(ray.direction);
  const double h = ray.altitude_m, mu = dir.y, mu_s = sun.y, nu = glm::dot(dir, sun);
  const double full = distance_to_exit(a, h, mu);
  const double end = std::min(full, ray.max_distance_m);
  auto t_of = [&](double s) { return end * s * s; };  // dense near the viewer
  // Psi_ms at kPsiNodes points (s = 0 .. 1), exactly.
  std::array<glm::dvec3, kPsiNodes> psi;
  tbb::parallel_for(0, kPsiNodes, [&](int k) {
    const ShellPoint p = shell_point(a, h, mu, mu_s, nu, t_of(static_cast<double>(k) / (kPsiNodes - 1)));
    psi[k] = reference_multiple_scattering(a, p.altitude_m, p.mu_s);
  });
  AtmosphereRadiance out;
  glm::dvec3 T(1.0), L(0.0);
  for (int k = 0; k < kViewSteps; ++k) {
    const double s0 = static_cast<double>(k) / kViewSteps, s1 = static_cast<double>(k + 1) / kViewSteps;
    const double t0 = t_of(s0), t1 = t_of(s1), dt = t1 - t0;
    const double sm = 0.5 * (s0 + s1);
    const ShellPoint p = shell_point(a, h, mu, mu_s, nu, 0.5 * (t0 + t1));
    const AtmosphereMedium m = atmosphere_medium(a, p.altitude_m);
    const double x = sm * (kPsiNodes - 1);
    const int i0 = std::min(static_cast<int>(x), kPsiNodes - 2);
    const glm::dvec3 psi_here = glm::mix(psi[i0], psi[i0 + 1], x - i0);
    const glm::dvec3 S = (m.rayleigh_scattering * rayleigh_phase(nu) + glm::dvec3(m.mie_scattering * cornette_shanks_phase(a.mie_g, nu))) *
                             sun_transmittance_exact(a, p.altitude_m, p.mu_s) +
                         m.scattering * psi_here;
    L += T * S * step_weight(m.extinction, dt);
    T *= glm::exp(-m.extinction * dt);
  }
  if (ray_hits_ground(a, h, mu) && ray.max_distance_m >= full) {
    // The ray ends on the sunlit Lambertian ground.
    const ShellPoint g = shell_point(a, h, mu, mu_s, nu, end);
    L += T * (a.ground_albedo / M_PI) * sun_transmittance_exact(a, 0.0, g.mu_s) * std::max(g.mu_s, 0.0);
  }
  out.inscattered_w_sr_m2 = L * a.solar_irradiance_w_m2;
  out.transmittance = T;
  return out;
}

}  // namespace nimbus::render
