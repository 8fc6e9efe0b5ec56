// Cameras framed on clouds (cloud_framing.hpp).
#include "nimbus/render/core/cloud_framing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nimbus::render {

Camera frame_clouds(Camera c, const std::vector<CloudVolume>& clouds, bool on_ground) {
  if (clouds.empty()) return c;
  glm::dvec3 lo, hi;
  cloud_bounds(clouds, lo, hi);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * glm::length(hi - lo);
  const double h_half = 0.5 * c.fov_deg * std::numbers::pi / 180.0;
  const double v_half = std::atan(std::tan(h_half) * c.height / c.width);
  double distance = 1.15 * radius / std::sin(std::min(h_half, v_half));
  glm::dvec3 back = c.eye - c.look_at;
  if (on_ground) back.y = 0.0;
  back = glm::length(back) > 0 ? glm::normalize(back) : glm::dvec3(0, 0, 1);
  c.look_at = centre;
  c.eye = centre + back * distance;
  if (on_ground) {
    const double eye_y = 2.0;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const double elevation = std::atan2(centre.y - eye_y, distance);  // of the clouds' centre
      const double angular_radius = std::asin(std::min(1.0, radius / std::hypot(distance, centre.y - eye_y)));
      const double pitch = std::max(0.0, elevation + angular_radius - 0.9 * v_half);
      c.eye = glm::dvec3(centre.x, eye_y, centre.z) + back * distance;
      c.look_at = c.eye - back * distance + glm::dvec3(0.0, distance * std::tan(pitch), 0.0);
      // The bottom fits too, and the horizon shows in the lower fifth or above.
      if (elevation - angular_radius >= pitch - 0.9 * v_half && pitch <= 0.6 * v_half) break;
      distance *= 1.2;
    }
  }
  c.near_m = std::max(1e-4, 1e-3 * radius);
  c.far_m = std::max(c.far_m, 4.0 * (glm::length(c.eye - centre) + radius));
  return c;
}

Camera frame_clouds_right_of(Camera c, const std::vector<CloudVolume>& clouds, bool on_ground, double covered_px) {
  const double covered = std::clamp(std::isfinite(covered_px) ? covered_px : 0.0, 0.0, 0.75 * c.width);
  if (covered < 1.0 || clouds.empty()) return frame_clouds(c, clouds, on_ground);
  const double tan_half = std::tan(0.5 * c.fov_deg * std::numbers::pi / 180.0);
  const double free_width = c.width - covered;
  Camera part = c;
  part.width = std::max(1, int(std::lround(free_width)));
  part.fov_deg = 2.0 * std::atan(tan_half * free_width / c.width) * 180.0 / std::numbers::pi;
  part = frame_clouds(part, clouds, on_ground);
  // The free part's centre lies covered / 2 pixels right of the picture's centre.
  const double turn = std::atan(tan_half * covered / c.width);
  const glm::dvec3 f = part.look_at - part.eye;
  // A left turn about y, the renderer's up: x' = x cos + z sin, z' = z cos - x sin.
  const glm::dvec3 turned{f.x * std::cos(turn) + f.z * std::sin(turn), f.y, f.z * std::cos(turn) - f.x * std::sin(turn)};
  c.eye = part.eye;
  c.look_at = part.eye + turned;
  c.near_m = part.near_m;
  c.far_m = part.far_m;
  return c;
}

Camera fit_far_plane(Camera c, const std::vector<CloudVolume>& clouds, double repeat_to_m) {
  if (clouds.empty()) return c;
  glm::dvec3 lo, hi;
  cloud_bounds(clouds, lo, hi);
  c.far_m = std::max(c.far_m, 4.0 * glm::length(hi - c.eye) + glm::length(hi - lo));
  // A copy is drawn when it comes within repeat_to_m of the eye; its far side is a tile further.
  if (repeat_to_m > 0.0)
    for (const CloudVolume& cloud : clouds)
      if (cloud.period_m.x > 0.0 || cloud.period_m.z > 0.0)
        c.far_m = std::max(c.far_m, 1.5 * (repeat_to_m + glm::length(cloud.world_max - cloud.world_min)));
  return c;
}

}  // namespace nimbus::render
