// A spot's airlight over a ray segment (spot_airlight.hpp): the cone crossings, the double
// reference in the angle psi, and shaders/lib/spot_airlight.glsl compiled as C++.
#include "nimbus/render/media/spot_airlight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/quadrature.hpp"
#include "nimbus/render/core/shader_contract.hpp"

// In an unnamed namespace: airlight_stable.cpp compiles lib/phase.glsl too, and each copy
// stays in its own translation unit.
namespace nimbus::render {
namespace {
namespace glsl {
using namespace glm;
using namespace ::nimbus::render::contract;  // lib/contract.glsl, already included: its guard skips it below
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"  // phase.glsl's functions the spot does not call
#include "lib/spot_airlight.glsl"
#pragma GCC diagnostic pop
}  // namespace glsl
}  // namespace
}  // namespace nimbus::render

namespace nimbus::render {
namespace {

constexpr double kPi = std::numbers::pi;

// The ray's plane through the lamp: c the lamp's foot on the ray, h its distance from the
// ray's line, m the unit way from the lamp to that line (spot_airlight.glsl's notation).
struct RayPlane {
  double c = 0.0, h = 0.0;
  glm::dvec3 m{0.0};
};

RayPlane ray_plane(const glm::dvec3& to_lamp, const glm::dvec3& dir) {
  RayPlane p;
  p.c = glm::dot(to_lamp, dir);
  const glm::dvec3 off = to_lamp - p.c * dir;
  p.h = glm::length(off);
  p.m = p.h > 0.0 ? -off / p.h : glm::dvec3(0.0);
  return p;
}

// The angles psi in (-pi/2, pi/2) where u(psi) . axis = cos_cone.
void cone_angles(double ma, double da, double cos_cone, std::vector<double>& out) {
  const double R = std::hypot(ma, da);
  if (!(R > 0.0) || std::abs(cos_cone) >= R) return;
  const double phi = std::atan2(da, ma), delta = std::acos(cos_cone / R);
  for (double turn : {-2.0 * kPi, 0.0, 2.0 * kPi})
    for (double psi : {phi - delta + turn, phi + delta + turn})
      if (psi > -0.5 * kPi && psi < 0.5 * kPi) out.push_back(psi);
}

}  // namespace

void validate(const SpotSegmentQuery& q) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("spot airlight " + what); };
  if (!(std::isfinite(q.sigma_t) && q.sigma_t >= 0.0)) fail("sigma_t must be finite and >= 0");
  if (!(std::isfinite(q.sigma_s) && q.sigma_s >= 0.0)) fail("sigma_s must be finite and >= 0");
  if (!(std::abs(glm::length(q.dir) - 1.0) <= 1e-9)) fail("dir must be a unit vector");
  if (!(std::isfinite(q.origin_m.x) && std::isfinite(q.origin_m.y) && std::isfinite(q.origin_m.z)))
    fail("origin_m must be finite");
  if (!(std::isfinite(q.x0) && q.x0 >= 0.0 && !std::isnan(q.x1) && q.x1 >= q.x0)) fail("segment must have 0 <= x0 <= x1");
  if (q.lamp.kind != LightKind::Point) fail("lamp must be a lamp, not the sun");
  validate(q.lamp);
}

std::vector<double> spot_cone_crossings(const Light& lamp, const glm::dvec3& origin_m, const glm::dvec3& dir) {
  std::vector<double> xs;
  if (!is_spot(lamp)) return xs;
  const RayPlane p = ray_plane(lamp.position_m - origin_m, dir);
  if (!(p.h > 0.0)) return xs;
  const glm::dvec3 axis = glm::normalize(lamp.spot_axis);
  std::vector<double> psis;
  for (double angle : {lamp.spot_inner_rad, lamp.spot_outer_rad})
    cone_angles(glm::dot(p.m, axis), glm::dot(dir, axis), std::cos(angle), psis);
  for (double psi : psis) {
    const double x = p.c + p.h * std::tan(psi);
    if (x >= 0.0) xs.push_back(x);
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

double spot_segment_airlight_reference(const SpotSegmentQuery& q) {
  validate(q);
  if (q.sigma_s == 0.0 || q.x1 == q.x0) return 0.0;
  const glm::dvec3 to_lamp = q.lamp.position_m - q.origin_m;
  RayPlane p = ray_plane(to_lamp, q.dir);
  if (!(p.h > 0.0)) {  // on the ray's line: the limit from a hair's breadth off it
    p.h = 1e-12 * std::max(glm::length(to_lamp), 1.0);
    p.m = glm::normalize(glm::cross(q.dir, std::abs(q.dir.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  }
  const double lo = std::atan((q.x0 - p.c) / p.h);
  const double hi = std::isinf(q.x1) ? 0.5 * kPi : std::atan((q.x1 - p.c) / p.h);
  std::vector<double> cuts;
  if (is_spot(q.lamp)) {
    const glm::dvec3 axis = glm::normalize(q.lamp.spot_axis);
    for (double angle : {q.lamp.spot_inner_rad, q.lamp.spot_outer_rad})
      cone_angles(glm::dot(p.m, axis), glm::dot(q.dir, axis), std::cos(angle), cuts);
  }
  const auto integrand = [&](double psi) {
    const double s = std::sin(psi), co = std::cos(psi);
    const glm::dvec3 u = co * p.m + s * q.dir;  // the light's propagation direction
    const double w = spot_weight(q.lamp, u);
    if (w == 0.0) return 0.0;
    const double xd = p.c + p.h * (s < 0.0 ? co / (1.0 - s) : (1.0 + s) / co);  // x + d
    return phase_value(q.phase, -s) * w * std::exp(-q.sigma_t * xd);
  };
  if (!(hi > lo)) return 0.0;
  const double integral = integrate_adaptive(integrand, lo, hi, cuts, 1e-10, 1e-300, 20000).value;
  return q.sigma_s * integral / p.h;
}

double spot_segment_airlight_float(const SpotSegmentQuery& q) {
  validate(q);
  const bool cone = is_spot(q.lamp);
  const glm::vec3 axis = cone ? glm::vec3(glm::normalize(q.lamp.spot_axis)) : glm::vec3(0.0f, 0.0f, 1.0f);
  const float cos_outer = cone ? static_cast<float>(std::cos(q.lamp.spot_outer_rad)) : -2.0f;
  const float cos_inner = cone ? static_cast<float>(std::cos(q.lamp.spot_inner_rad)) : -2.0f;
  const float x1 = std::isinf(q.x1) ? 1.0e30f : static_cast<float>(std::min(q.x1, 1.0e30));
  return glsl::spot_segment_airlight(static_cast<float>(q.sigma_t), static_cast<float>(q.sigma_s),
                                     glm::vec3(q.lamp.position_m - q.origin_m), glm::vec3(q.dir), axis, cos_outer,
                                     cos_inner, static_cast<float>(q.x0), x1, phase_code(q.phase.kind),
                                     static_cast<float>(q.phase.g));
}

}  // namespace nimbus::render
