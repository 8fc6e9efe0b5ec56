// Building and reading the physical sky's tables (atmosphere_tables.hpp, Hillaire 2020 section 4).
#include "nimbus/render/media/atmosphere_tables.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/base/cancel.hpp"

namespace nimbus::render {
namespace glsl {
using namespace glm;
#include "lib/atmosphere_map.glsl"
}  // namespace glsl

namespace {

constexpr int kTransmittanceSteps = 64;  // midpoint steps to the top per transmittance texel
constexpr int kMsDirections = 64;         // directions per multiple-scattering texel (Fibonacci sphere), as Hillaire
constexpr int kMsSteps = 30;              // steps per direction
constexpr int kSkySteps = 40;             // steps per sky-view texel
constexpr int kApSubsteps = 4;            // steps between two aerial-perspective depths

float f(double x) { return static_cast<float>(x); }

AtmosphereTable make_table(int w, int h, int d = 1) {
  AtmosphereTable t;
  t.width = w;
  t.height = h;
  t.depth = d;
  t.texels.assign(static_cast<size_t>(w) * h * d, glm::vec3(0.0f));
  return t;
}

// Radiance scattered toward the viewer per unit solar irradiance at one point (Hillaire eq. 3
// with Psi_ms for the higher orders): single scattering by both phases plus sigma_s Psi_ms.
glm::dvec3 scattering_source(const AtmosphereTables& t, const AtmosphereMedium& m, const ShellPoint& p, double nu) {
  const glm::dvec3 sun = table_transmittance(t, p.altitude_m, p.mu_s) * sun_visibility(t.atmosphere, p.altitude_m, p.mu_s);
  const glm::dvec3 single =
      (m.rayleigh_scattering * rayleigh_phase(nu) + glm::dvec3(m.mie_scattering * cornette_shanks_phase(t.atmosphere.mie_g, nu))) * sun;
  return single + m.scattering * table_multiple_scattering(t, p.altitude_m, p.mu_s);
}

// Marches a ray from (h, mu) for [t0, t1] in n steps whose ends are t0 + (t1 - t0) s^2 (dense
// near the start, where the air is densest for rays from the ground), adding to L and T.
void march(const AtmosphereTables& t, double h, double mu, double mu_s, double nu, double t0, double t1, int n, bool quadratic,
           glm::dvec3& L, glm::dvec3& T) {
  for (int k = 0; k < n; ++k) {
    const double s0 = static_cast<double>(k) / n, s1 = static_cast<double>(k + 1) / n;
    const double a0 = t0 + (t1 - t0) * (quadratic ? s0 * s0 : s0);
    const double a1 = t0 + (t1 - t0) * (quadratic ? s1 * s1 : s1);
    const double dt = a1 - a0;
    const ShellPoint p = shell_point(t.atmosphere, h, mu, mu_s, nu, 0.5 * (a0 + a1));
    const AtmosphereMedium m = atmosphere_medium(t.atmosphere, p.altitude_m);
    L += T * scattering_source(t, m, p, nu) * step_weight(m.extinction, dt);
    T *= glm::exp(-m.extinction * dt);
  }
}

void build_transmittance(AtmosphereTables& t) {
  const Atmosphere& a = t.atmosphere;
  t.transmittance = make_table(glsl::ATM_TRANSMITTANCE_W, glsl::ATM_TRANSMITTANCE_H);
  const std::stop_token stop = current_stop_token();  // this call's, polled a row at a time (cancel.hpp)
  tbb::parallel_for(0, t.transmittance.height, [&](int y) {
    throw_if_stopped(stop);
    for (int x = 0; x < t.transmittance.width; ++x) {
      const TransmittanceTexel q = transmittance_texel(a, x, y);
      const double d = distance_to_top(a, q.altitude_m, q.mu);
      glm::dvec3 tau(0.0);
      for (int k = 0; k < kTransmittanceSteps; ++k) {
        const double tm = (k + 0.5) * d / kTransmittanceSteps;
        const ShellPoint p = shell_point(a, q.altitude_m, q.mu, 0.0, 0.0, tm);
        tau += atmosphere_medium(a, p.altitude_m).extinction * (d / kTransmittanceSteps);
      }
      const glm::dvec3 T = glm::exp(-tau);
      t.transmittance.texels[static_cast<size_t>(y) * t.transmittance.width + x] = glm::vec3(T);
    }
  });
}

// Hillaire section 5.5: the second order L2 and the transfer f_ms of an isotropic unit field,
// each the mean over the sphere of directions; Psi_ms = L2 / (1 - f_ms) sums every higher order.
void build_multiple_scattering(AtmosphereTables& t) {
  const Atmosphere& a = t.atmosphere;
  t.multiple_scattering = make_table(glsl::ATM_MS_W, glsl::ATM_MS_H);
  const double thickness = a.top_radius_m - a.bottom_radius_m;
  const std::stop_token stop = current_stop_token();  // this call's, polled a row at a time (cancel.hpp)
  tbb::parallel_for(0, t.multiple_scattering.height, [&](int y) {
    throw_if_stopped(stop);
    for (int x = 0; x < t.multiple_scattering.width; ++x) {
      const double w = 2.0 * x / (t.multiple_scattering.width - 1) - 1.0;  // sign(mu_s) sqrt|mu_s|
      const double mu_s = std::clamp(w * std::abs(w), -1.0, 1.0);
      const double v = static_cast<double>(y) / (t.multiple_scattering.height - 1);
      const double h = thickness * v * v;
      const glm::dvec3 sun_dir{std::sqrt(std::max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0};
      glm::dvec3 L2(0.0), fms(0.0);
      for (int i = 0; i < kMsDirections; ++i) {
        const glm::dvec3 dir = fibonacci_sphere(i, kMsDirections);
        const double mu = dir.y;
        const double nu = glm::dot(dir, sun_dir);
        const bool ground = ray_hits_ground(a, h, mu);
        const double end = distance_to_exit(a, h, mu);
        glm::dvec3 L(0.0), fsum(0.0), T(1.0);
        for (int k = 0; k < kMsSteps; ++k) {
          const double a0 = end * k / kMsSteps, a1 = end * (k + 1) / kMsSteps, dt = a1 - a0;
          const ShellPoint p = shell_point(a, h, mu, mu_s, nu, 0.5 * (a0 + a1));
          const AtmosphereMedium m = atmosphere_medium(a, p.altitude_m);
          const glm::dvec3 w = T * step_weight(m.extinction, dt);
          const glm::dvec3 sun = table_transmittance(t, p.altitude_m, p.mu_s) * sun_visibility(a, p.altitude_m, p.mu_s);
          L += w * m.scattering * sun / (4.0 * M_PI);  // isotropic phase
          fsum += w * m.scattering;
          T *= glm::exp(-m.extinction * dt);
        }
        if (ground) {
          const ShellPoint g = shell_point(a, h, mu, mu_s, nu, end);
          const double mu_g = std::max(g.mu_s, 0.0);
          L += T * table_transmittance(t, 0.0, mu_g) * sun_visibility(a, 0.0, g.mu_s) * (a.ground_albedo / M_PI) * mu_g;
        }
        L2 += L / static_cast<double>(kMsDirections);
        fms += fsum / static_cast<double>(kMsDirections);
      }
      const glm::dvec3 psi = L2 / glm::max(1.0 - fms, glm::dvec3(1.0e-6));
      t.multiple_scattering.texels[static_cast<size_t>(y) * t.multiple_scattering.width + x] = glm::vec3(psi);
    }
  });
}

void build_sky_view(AtmosphereTables& t) {
  const Atmosphere& a = t.atmosphere;
  const double h = t.view.altitude_m;
  const double mu_s = glm::normalize(t.view.direction_to_sun).y;
  const glm::dvec3 E = a.solar_irradiance_w_m2;
  t.sky_view = make_table(glsl::ATM_SKY_W, glsl::ATM_SKY_H);
  const std::stop_token stop = current_stop_token();  // this call's, polled a row at a time (cancel.hpp)
  tbb::parallel_for(0, t.sky_view.height, [&](int y) {
    throw_if_stopped(stop);
    for (int x = 0; x < t.sky_view.width; ++x) {
      const ViewTexel q = view_texel(a, h, static_cast<double>(x) / (t.sky_view.width - 1), static_cast<double>(y) / (t.sky_view.height - 1));
      const double sin_s = std::sqrt(std::max(1.0 - mu_s * mu_s, 0.0));
      const double sin_t = std::sqrt(std::max(1.0 - q.cos_theta * q.cos_theta, 0.0));
      const double nu = mu_s * q.cos_theta + sin_s * sin_t * q.cos_phi;
      glm::dvec3 L(0.0), T(1.0);
      const double end = distance_to_exit(a, h, q.cos_theta);
      march(t, h, q.cos_theta, mu_s, nu, 0.0, end, kSkySteps, true, L, T);
      if (ray_hits_ground(a, h, q.cos_theta)) {
        // The ground far away, lit by the sun: T albedo / pi E_sun mu_s (Lambertian).
        const ShellPoint g = shell_point(a, h, q.cos_theta, mu_s, nu, end);
        L += T * (a.ground_albedo / M_PI) * table_transmittance(t, 0.0, g.mu_s) * sun_visibility(a, 0.0, g.mu_s) * std::max(g.mu_s, 0.0);
      }
      t.sky_view.texels[static_cast<size_t>(y) * t.sky_view.width + x] = glm::vec3(L * E);
    }
  });
}

void build_aerial_perspective(AtmosphereTables& t) {
  const Atmosphere& a = t.atmosphere;
  const double h = t.view.altitude_m;
  const double mu_s = glm::normalize(t.view.direction_to_sun).y;
  const glm::dvec3 E = a.solar_irradiance_w_m2;
  t.aerial_scattering = make_table(glsl::ATM_AP_W, glsl::ATM_AP_H, glsl::ATM_AP_D);
  t.aerial_transmittance = make_table(glsl::ATM_AP_W, glsl::ATM_AP_H, glsl::ATM_AP_D);
  const int W = glsl::ATM_AP_W, H = glsl::ATM_AP_H, D = glsl::ATM_AP_D;
  const std::stop_token stop = current_stop_token();  // this call's, polled a row at a time (cancel.hpp)
  tbb::parallel_for(0, H, [&](int y) {
    throw_if_stopped(stop);
    for (int x = 0; x < W; ++x) {
      const ViewTexel q = view_texel(a, h, static_cast<double>(x) / (W - 1), static_cast<double>(y) / (H - 1));
      const double sin_s = std::sqrt(std::max(1.0 - mu_s * mu_s, 0.0));
      const double sin_t = std::sqrt(std::max(1.0 - q.cos_theta * q.cos_theta, 0.0));
      const double nu = mu_s * q.cos_theta + sin_s * sin_t * q.cos_phi;
      const double end = distance_to_exit(a, h, q.cos_theta);
      glm::dvec3 L(0.0), T(1.0);
      double prev = 0.0;
      for (int z = 0; z < D; ++z) {
        const double w = static_cast<double>(z) / (D - 1);
        const double d = std::min(t.view.aerial_max_distance_m * w * w, end);
        if (d > prev) march(t, h, q.cos_theta, mu_s, nu, prev, d, kApSubsteps, false, L, T);
        prev = std::max(prev, d);
        const size_t i = (static_cast<size_t>(z) * H + y) * W + x;
        t.aerial_scattering.texels[i] = glm::vec3(L * E);
        t.aerial_transmittance.texels[i] = glm::vec3(T);
      }
    }
  });
}

// The sky's light on an upward surface and its mean radiance, from the sky-view table (midpoint
// rule, 64 x 32 directions over the upper hemisphere).
void integrate_sky(AtmosphereTables& t) {
  const int nt = 32, np = 64;
  glm::dvec3 E(0.0), mean(0.0);
  for (int i = 0; i < nt; ++i) {
    const double th = (i + 0.5) * 0.5 * M_PI / nt;
    for (int j = 0; j < np; ++j) {
      const double ph = (j + 0.5) * 2.0 * M_PI / np;
      const glm::dvec3 dir{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)};
      const glm::dvec3 L = table_sky_radiance(t, dir);
      const double dw = std::sin(th) * (0.5 * M_PI / nt) * (2.0 * M_PI / np);
      E += L * std::cos(th) * dw;
      mean += L * dw;
    }
  }
  t.sky_irradiance_up_w_m2 = E;
  t.sky_mean_radiance_w_sr_m2 = mean / (2.0 * M_PI);
}

}  // namespace

glm::vec3 AtmosphereTable::bilinear(glm::vec2 c, int z) const {
  const float x = std::clamp(c.x, 0.0f, static_cast<float>(width - 1));
  const float y = std::clamp(c.y, 0.0f, static_cast<float>(height - 1));
  const int x0 = std::min(static_cast<int>(x), width - 1), y0 = std::min(static_cast<int>(y), height - 1);
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const float fx = x - x0, fy = y - y0;
  return glm::mix(glm::mix(at(x0, y0, z), at(x1, y0, z), fx), glm::mix(at(x0, y1, z), at(x1, y1, z), fx), fy);
}

glm::vec3 AtmosphereTable::trilinear(glm::vec3 c) const {
  const float z = std::clamp(c.z, 0.0f, static_cast<float>(depth - 1));
  const int z0 = std::min(static_cast<int>(z), depth - 1), z1 = std::min(z0 + 1, depth - 1);
  return glm::mix(bilinear({c.x, c.y}, z0), bilinear({c.x, c.y}, z1), z - z0);
}

void validate(const Atmosphere& a, const AtmosphereView& v) {
  validate(a);
  const double thickness = a.top_radius_m - a.bottom_radius_m;
  if (!(std::isfinite(v.altitude_m) && v.altitude_m >= 0.0 && v.altitude_m <= thickness - 1000.0))
    throw std::invalid_argument("atmosphere view altitude_m: must be in [0, " + std::to_string(thickness - 1000.0) + "] m, got " +
                                std::to_string(v.altitude_m));
  const glm::dvec3 s = v.direction_to_sun;
  if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z)) || glm::length(s) < 1.0e-12)
    throw std::invalid_argument("atmosphere view direction_to_sun: must be finite and non-zero");
  if (!(std::isfinite(v.aerial_max_distance_m) && v.aerial_max_distance_m > 0.0 && v.aerial_max_distance_m <= 1.0e6))
    throw std::invalid_argument("atmosphere view aerial_max_distance_m: must be in (0, 1e6] m");
}

std::shared_ptr<const AtmosphereTables> build_atmosphere_tables(const Atmosphere& a, const AtmosphereView& v,
                                                                const std::shared_ptr<const AtmosphereTables>& previous) {
  validate(a, v);
  auto start = std::chrono::steady_clock::now();
  auto t = std::make_shared<AtmosphereTables>();
  t->atmosphere = a;
  t->view = v;
  t->view.direction_to_sun = glm::normalize(v.direction_to_sun);
  auto lap = [&start]() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start).count();
    start = now;
    return ms;
  };
  if (previous && previous->atmosphere == a) {
    // The sun's position changes the sky view and the aerial perspective only.
    t->transmittance = previous->transmittance;
    t->multiple_scattering = previous->multiple_scattering;
  } else {
    build_transmittance(*t);
    t->timing.transmittance_ms = lap();
    build_multiple_scattering(*t);
    t->timing.multiple_scattering_ms = lap();
  }
  lap();
  build_sky_view(*t);
  t->timing.sky_view_ms = lap();
  build_aerial_perspective(*t);
  integrate_sky(*t);
  t->timing.aerial_perspective_ms = lap();
  return t;
}

TransmittanceTexel transmittance_texel(const Atmosphere& a, int x, int y) {
  const double R = a.bottom_radius_m, Rt = a.top_radius_m;
  const double H = std::sqrt((Rt - R) * (Rt + R));
  const double x_mu = static_cast<double>(x) / (glsl::ATM_TRANSMITTANCE_W - 1);
  const double x_r = static_cast<double>(y) / (glsl::ATM_TRANSMITTANCE_H - 1);
  const double rho = H * x_r;
  const double r = std::sqrt(rho * rho + R * R);
  const double h = rho * rho / (r + R);
  const double d_min = Rt - r, d_max = rho + H;
  const double d = d_min + x_mu * (d_max - d_min);
  const double mu = d <= 0.0 ? 1.0 : std::clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
  return {h, mu};
}

ViewTexel view_texel(const Atmosphere& a, double viewer_altitude_m, double u, double v) {
  const double theta_h = std::acos(horizon_cos(a, viewer_altitude_m));
  const double phi = M_PI * u * u;
  const double theta = v < 0.5 ? theta_h * (1.0 - (1.0 - 2.0 * v) * (1.0 - 2.0 * v))
                               : theta_h + (M_PI - theta_h) * (2.0 * v - 1.0) * (2.0 * v - 1.0);
  return {std::cos(phi), std::cos(theta)};
}

ViewAngles view_angles(const glm::dvec3& direction_to_sun, const glm::dvec3& dir) {
  const glm::dvec3 s = glm::normalize(direction_to_sun), d = glm::normalize(dir);
  const glm::dvec2 sh{s.x, s.z}, dh{d.x, d.z};
  const double ls = glm::length(sh), ld = glm::length(dh);
  const double cos_phi = ls > 1.0e-9 && ld > 1.0e-9 ? glm::dot(sh, dh) / (ls * ld) : 1.0;
  return {std::clamp(cos_phi, -1.0, 1.0), std::clamp(d.y, -1.0, 1.0), std::clamp(glm::dot(s, d), -1.0, 1.0)};
}

glm::dvec3 table_transmittance(const AtmosphereTables& t, double altitude_m, double mu) {
  const Atmosphere& a = t.atmosphere;
  const double m = std::max(mu, horizon_cos(a, altitude_m));
  return glm::dvec3(t.transmittance.bilinear(glsl::atm_transmittance_coord(f(a.bottom_radius_m), f(a.top_radius_m), f(altitude_m), f(m))));
}

glm::dvec3 table_sun_irradiance(const AtmosphereTables& t, double altitude_m, double mu_s) {
  return t.atmosphere.solar_irradiance_w_m2 * table_transmittance(t, altitude_m, mu_s) * sun_visibility(t.atmosphere, altitude_m, mu_s);
}

glm::dvec3 table_multiple_scattering(const AtmosphereTables& t, double altitude_m, double mu_s) {
  const Atmosphere& a = t.atmosphere;
  return glm::dvec3(t.multiple_scattering.bilinear(glsl::atm_ms_coord(f(a.top_radius_m - a.bottom_radius_m), f(altitude_m), f(mu_s))));
}

namespace {
glm::vec2 view_coord(const AtmosphereTables& t, const glm::dvec3& dir, int w, int h) {
  const ViewAngles v = view_angles(t.view.direction_to_sun, dir);
  const glm::vec2 uv = glsl::atm_view_uv(f(v.cos_phi), f(v.cos_theta), f(horizon_cos(t.atmosphere, t.view.altitude_m)));
  return uv * glm::vec2(static_cast<float>(w - 1), static_cast<float>(h - 1));
}
}  // namespace

glm::dvec3 table_sky_radiance(const AtmosphereTables& t, const glm::dvec3& dir) {
  return glm::dvec3(t.sky_view.bilinear(view_coord(t, dir, t.sky_view.width, t.sky_view.height)));
}

AerialPerspective table_aerial_perspective(const AtmosphereTables& t, const glm::dvec3& dir, double distance_m) {
  const glm::vec2 c = view_coord(t, dir, t.aerial_scattering.width, t.aerial_scattering.height);
  const glm::vec3 c3{c, glsl::atm_ap_depth(f(distance_m), f(t.view.aerial_max_distance_m))};
  return {glm::dvec3(t.aerial_scattering.trilinear(c3)), glm::dvec3(t.aerial_transmittance.trilinear(c3))};
}

}  // namespace nimbus::render
