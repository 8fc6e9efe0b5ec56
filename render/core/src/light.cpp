// The sun and the lamps (light.hpp).
#include "nimbus/render/core/light.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "nimbus/base/validate.hpp"

namespace nimbus::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void require_colour(const glm::dvec3& c, const std::string& field) {
  for (int k = 0; k < 3; ++k)
    require(std::isfinite(c[k]) && c[k] >= 0.0, "light " + field + " must be finite and >= 0 per channel");
}

double smoothstep(double e0, double e1, double x) {
  if (!(e1 > e0)) return x >= e1 ? 1.0 : 0.0;  // a hard cone (inner == outer)
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

Light point_light(const glm::dvec3& position_m, const glm::dvec3& intensity_w_sr, const glm::dvec3& spot_axis,
                  double spot_inner_rad, double spot_outer_rad) {
  Light l;
  l.kind = LightKind::Point;
  l.position_m = position_m;
  l.intensity_w_sr = intensity_w_sr;
  l.spot_axis = spot_axis;
  l.spot_inner_rad = spot_inner_rad;
  l.spot_outer_rad = spot_outer_rad;
  return l;
}

Light sun_light(const glm::dvec3& direction_to_sun, const glm::dvec3& irradiance_w_m2) {
  Light l;
  l.kind = LightKind::Sun;
  l.direction_to_sun = direction_to_sun;
  l.irradiance_w_m2 = irradiance_w_m2;
  return l;
}

Light bulb_light(const glm::dvec3& position_m, const glm::dvec3& intensity_w_sr, double bulb_radius_m) {
  Light l = point_light(position_m, intensity_w_sr);
  l.bulb_radius_m = bulb_radius_m;
  return l;
}

void validate(const Light& l) {
  if (l.kind == LightKind::Sun) {
    require(finite3(l.direction_to_sun) && glm::length(l.direction_to_sun) >= kMinSunDirectionLength,
            "light direction_to_sun must be finite and at least " + number_text(kMinSunDirectionLength) + " long");
    require_colour(l.irradiance_w_m2, "irradiance_w_m2");
    return;
  }
  require(l.kind == LightKind::Point, "light kind must be sun or point");
  require(finite3(l.position_m), "light position_m must be finite");
  require_colour(l.intensity_w_sr, "intensity_w_sr");
  require(std::isfinite(l.min_distance_m) && l.min_distance_m > 0.0, "light min_distance_m must be finite and > 0");
  require(std::isfinite(l.bulb_radius_m) && l.bulb_radius_m >= 0.0, "light bulb_radius_m must be finite and >= 0");
  require(finite3(l.spot_axis), "light spot_axis must be finite");
  require(valid_spot_cone(l), "light spot cone must have 0 < spot_inner_rad <= spot_outer_rad <= pi");
}

bool is_spot(const Light& l) { return l.kind == LightKind::Point && glm::length(l.spot_axis) > 0.0; }

bool valid_spot_cone(const Light& l) {
  return !is_spot(l) || (std::isfinite(l.spot_inner_rad) && std::isfinite(l.spot_outer_rad) && l.spot_inner_rad > 0.0 &&
                         l.spot_inner_rad <= l.spot_outer_rad && l.spot_outer_rad <= kPi);
}

bool any_spot(const std::vector<Light>& lights) { return std::any_of(lights.begin(), lights.end(), is_spot); }

double spot_weight(const Light& l, const glm::dvec3& dir) {
  if (!is_spot(l)) return 1.0;
  const double c = glm::dot(dir, glm::normalize(l.spot_axis));
  return smoothstep(std::cos(l.spot_outer_rad), std::cos(l.spot_inner_rad), c);
}

LightAtPoint light_at(const Light& l, const glm::dvec3& x) {
  LightAtPoint a;
  if (l.kind == LightKind::Sun) {
    a.to_light = glm::normalize(l.direction_to_sun);
    a.distance_m = std::numeric_limits<double>::infinity();
    a.irradiance_w_m2 = l.irradiance_w_m2;
    return a;
  }
  const glm::dvec3 d = l.position_m - x;
  const double r = glm::length(d);
  a.distance_m = r;
  a.to_light = r > 0.0 ? d / r : glm::dvec3(0.0, 1.0, 0.0);
  const double rr = std::max(r, l.min_distance_m);
  a.irradiance_w_m2 = l.intensity_w_sr * (spot_weight(l, -a.to_light) / (rr * rr));  // I / r^2
  return a;
}

double light_strength_at(const Light& l, const glm::dvec3& x) {
  const glm::dvec3 e = light_at(l, x).irradiance_w_m2;
  return std::max({e.x, e.y, e.z});
}

std::vector<int> strongest_lights(const std::vector<Light>& lights, const glm::dvec3& x, int max_lights) {
  std::vector<int> order(lights.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> strength(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) strength[i] = light_strength_at(lights[i], x);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return strength[a] > strength[b]; });
  if (max_lights >= 0 && order.size() > static_cast<std::size_t>(max_lights)) order.resize(max_lights);
  return order;
}

}  // namespace nimbus::render
