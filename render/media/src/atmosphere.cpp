// The atmosphere's media, phase functions and shell geometry (atmosphere.hpp).
#include "nimbus/render/media/atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nimbus::render {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument("atmosphere." + field + ": " + why);
}

void non_negative(const std::string& field, double v) {
  if (!std::isfinite(v) || v < 0.0) fail(field, "must be finite and >= 0, got " + std::to_string(v));
}

void non_negative(const std::string& field, const glm::dvec3& v) {
  for (int i = 0; i < 3; ++i) non_negative(field, v[i]);
}

}  // namespace

void validate(const Atmosphere& a) {
  if (!(std::isfinite(a.bottom_radius_m) && a.bottom_radius_m >= 1000.0 && a.bottom_radius_m <= 1.0e8))
    fail("bottom_radius_m", "must be in [1 km, 1e5 km]");
  if (!(std::isfinite(a.top_radius_m) && a.top_radius_m > a.bottom_radius_m + 100.0 && a.top_radius_m <= 2.0 * a.bottom_radius_m))
    fail("top_radius_m", "must exceed bottom_radius_m by at least 100 m and be at most twice it");
  non_negative("rayleigh_scattering_per_m", a.rayleigh_scattering_per_m);
  non_negative("mie_scattering_per_m", a.mie_scattering_per_m);
  if (!(std::isfinite(a.mie_extinction_per_m) && a.mie_extinction_per_m >= a.mie_scattering_per_m))
    fail("mie_extinction_per_m", "must be finite and >= mie_scattering_per_m");
  non_negative("ozone_absorption_per_m", a.ozone_absorption_per_m);
  if (!(std::isfinite(a.rayleigh_scale_height_m) && a.rayleigh_scale_height_m > 0.0)) fail("rayleigh_scale_height_m", "must be > 0");
  if (!(std::isfinite(a.mie_scale_height_m) && a.mie_scale_height_m > 0.0)) fail("mie_scale_height_m", "must be > 0");
  if (!(std::isfinite(a.mie_g) && a.mie_g > -1.0 && a.mie_g < 1.0)) fail("mie_g", "must be in (-1, 1)");
  non_negative("ozone_centre_m", a.ozone_centre_m);
  if (!(std::isfinite(a.ozone_half_width_m) && a.ozone_half_width_m > 0.0)) fail("ozone_half_width_m", "must be > 0");
  if (!(std::isfinite(a.ground_albedo) && a.ground_albedo >= 0.0 && a.ground_albedo <= 1.0)) fail("ground_albedo", "must be in [0, 1]");
  non_negative("solar_irradiance_w_m2", a.solar_irradiance_w_m2);
  if (!(std::isfinite(a.sun_angular_radius_rad) && a.sun_angular_radius_rad > 0.0 && a.sun_angular_radius_rad < 0.1))
    fail("sun_angular_radius_rad", "must be in (0, 0.1)");
}

AtmosphereMedium atmosphere_medium(const Atmosphere& a, double altitude_m) {
  const double h = std::max(altitude_m, 0.0);
  const double rayleigh = std::exp(-h / a.rayleigh_scale_height_m);
  const double mie = std::exp(-h / a.mie_scale_height_m);
  const double ozone = std::max(0.0, 1.0 - std::abs(h - a.ozone_centre_m) / a.ozone_half_width_m);
  AtmosphereMedium m;
  m.rayleigh_scattering = a.rayleigh_scattering_per_m * rayleigh;
  m.mie_scattering = a.mie_scattering_per_m * mie;
  m.scattering = m.rayleigh_scattering + glm::dvec3(m.mie_scattering);
  m.extinction = m.rayleigh_scattering + glm::dvec3(a.mie_extinction_per_m * mie) + a.ozone_absorption_per_m * ozone;
  return m;
}

double rayleigh_phase(double mu) { return 3.0 * (1.0 + mu * mu) / (16.0 * M_PI); }

double cornette_shanks_phase(double g, double mu) {
  const double g2 = g * g;
  const double denom = std::max(1.0 + g2 - 2.0 * g * mu, 1.0e-12);
  return 3.0 * (1.0 - g2) * (1.0 + mu * mu) / (8.0 * M_PI * (2.0 + g2) * denom * std::sqrt(denom));
}

double horizon_cos(const Atmosphere& a, double altitude_m) {
  const double h = std::max(altitude_m, 0.0);
  return -std::sqrt(h * (2.0 * a.bottom_radius_m + h)) / (a.bottom_radius_m + h);
}

bool ray_hits_ground(const Atmosphere& a, double altitude_m, double mu) {
  return mu < 0.0 && mu < horizon_cos(a, altitude_m);
}

double distance_to_top(const Atmosphere& a, double altitude_m, double mu) {
  const double r = a.bottom_radius_m + std::max(altitude_m, 0.0);
  const double R = a.top_radius_m;
  const double k = std::max((R - r) * (R + r), 0.0);  // R^2 - r^2
  const double root = std::sqrt(std::max(k + r * r * mu * mu, 0.0));
  return mu >= 0.0 ? k / std::max(r * mu + root, 1.0e-9) : root - r * mu;
}

double distance_to_ground(const Atmosphere& a, double altitude_m, double mu) {
  const double h = std::max(altitude_m, 0.0);
  const double r = a.bottom_radius_m + h;
  const double k = h * (2.0 * a.bottom_radius_m + h);  // r^2 - R_ground^2
  const double root = std::sqrt(std::max(r * r * mu * mu - k, 0.0));
  return k / std::max(-r * mu + root, 1.0e-9);
}

double distance_to_exit(const Atmosphere& a, double altitude_m, double mu) {
  return ray_hits_ground(a, altitude_m, mu) ? distance_to_ground(a, altitude_m, mu) : distance_to_top(a, altitude_m, mu);
}

glm::dvec3 step_weight(const glm::dvec3& sigma, double dt) {
  glm::dvec3 w;
  for (int c = 0; c < 3; ++c) {
    const double y = sigma[c] * dt;
    w[c] = y < 1.0e-6 ? dt * (1.0 - 0.5 * y) : -std::expm1(-y) / sigma[c];
  }
  return w;
}

ShellPoint shell_point(const Atmosphere& a, double altitude_m, double mu, double mu_s, double nu, double t_m) {
  const double R = a.bottom_radius_m;
  const double h = std::max(altitude_m, 0.0);
  const double r = R + h;
  // r'^2 - R^2 = h (2R + h) + t^2 + 2 r t mu, without cancelling r'^2 against R^2.
  const double k = h * (2.0 * R + h) + t_m * t_m + 2.0 * r * t_m * mu;
  const double r2 = std::sqrt(std::max(R * R + k, 0.0));
  ShellPoint p;
  p.altitude_m = std::max(k / (r2 + R), 0.0);
  p.mu = std::clamp((r * mu + t_m) / r2, -1.0, 1.0);
  p.mu_s = std::clamp((r * mu_s + t_m * nu) / r2, -1.0, 1.0);
  return p;
}

glm::dvec3 fibonacci_sphere(int i, int n) {
  const double mu = 1.0 - (2.0 * i + 1.0) / n;
  const double phi = i * M_PI * (3.0 - std::sqrt(5.0));
  const double s = std::sqrt(std::max(1.0 - mu * mu, 0.0));
  return {s * std::cos(phi), mu, s * std::sin(phi)};
}

double sun_visibility(const Atmosphere& a, double altitude_m, double mu_s) {
  const double mu_h = horizon_cos(a, altitude_m);
  // near the horizon d(mu) = sin(theta) d(theta), sin(theta) ~ 1
  const double half = a.sun_angular_radius_rad * std::sqrt(std::max(1.0 - mu_h * mu_h, 1.0e-6));
  return std::clamp((mu_s - mu_h) / (2.0 * half) + 0.5, 0.0, 1.0);
}

}  // namespace nimbus::render
