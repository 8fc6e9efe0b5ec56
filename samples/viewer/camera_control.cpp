// Orbit and fly camera moves (camera_control.hpp).
#include "camera_control.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus::viewer {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kMaxPitch = 89.0 * kDeg;
const glm::dvec3 kUp{0.0, 1.0, 0.0};

// Direction from (yaw, pitch): yaw about +y from -z, pitch up from the horizon.
glm::dvec3 direction(double yaw, double pitch) {
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

void angles(const glm::dvec3& d, double& yaw, double& pitch) {
  const glm::dvec3 n = glm::normalize(d);
  pitch = std::asin(std::clamp(n.y, -1.0, 1.0));
  yaw = std::atan2(n.x, -n.z);
}

}  // namespace

CameraPose tumble(const CameraPose& p, double dx, double dy) {
  const glm::dvec3 offset = p.eye - p.look_at;  // from the target to the eye
  const double r = glm::length(offset);
  double yaw = 0, pitch = 0;
  angles(offset, yaw, pitch);
  yaw -= dx * 0.3 * kDeg;
  pitch = std::clamp(pitch + dy * 0.3 * kDeg, -kMaxPitch, kMaxPitch);
  return {p.look_at + r * direction(yaw, pitch), p.look_at};
}

CameraPose pan(const CameraPose& p, double dx, double dy, double fov_deg, int width_px) {
  const glm::dvec3 f = glm::normalize(p.look_at - p.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(f, kUp));
  const glm::dvec3 up = glm::cross(right, f);
  const double metres_per_px =
      2.0 * glm::length(p.look_at - p.eye) * std::tan(0.5 * fov_deg * kDeg) / std::max(width_px, 1);
  const glm::dvec3 move = (-dx * right + dy * up) * metres_per_px;
  return {p.eye + move, p.look_at + move};
}

CameraPose zoom(const CameraPose& p, double notches) {
  const glm::dvec3 offset = p.eye - p.look_at;
  const double r = std::clamp(glm::length(offset) * std::pow(0.9, notches), 1.0, 200000.0);
  return {p.look_at + r * glm::normalize(offset), p.look_at};
}

CameraPose fly_look(const CameraPose& p, double dx, double dy) {
  const glm::dvec3 view = p.look_at - p.eye;
  const double r = glm::length(view);
  double yaw = 0, pitch = 0;
  angles(view, yaw, pitch);
  yaw += dx * 0.2 * kDeg;
  pitch = std::clamp(pitch - dy * 0.2 * kDeg, -kMaxPitch, kMaxPitch);
  return {p.eye, p.eye + r * direction(yaw, pitch)};
}

CameraPose fly_move(const CameraPose& p, const glm::dvec3& move, double speed, double dt) {
  const glm::dvec3 f = glm::normalize(p.look_at - p.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(f, kUp));
  const glm::dvec3 step = (move.x * right + move.y * kUp + move.z * f) * speed * dt;
  return {p.eye + step, p.look_at + step};
}

CameraPose keep_eye_above(const CameraPose& p, double min_y) {
  if (!(p.eye.y < min_y)) return p;
  const glm::dvec3 offset = p.eye - p.look_at;
  const double r = glm::length(offset);
  if (p.look_at.y > min_y && r > 0.0) {
    // look_at.y + r sin(pitch) = min_y, a pitch in (-90, 0) degrees.
    double yaw = 0, pitch = 0;
    angles(offset, yaw, pitch);
    pitch = std::asin(std::clamp((min_y - p.look_at.y) / r, -1.0, 1.0));
    CameraPose out{p.look_at + r * direction(yaw, pitch), p.look_at};
    out.eye.y = std::max(out.eye.y, min_y);  // not a rounding error under it
    return out;
  }
  const glm::dvec3 rise(0.0, min_y - p.eye.y, 0.0);
  return {p.eye + rise, p.look_at + rise};
}

}  // namespace nimbus::viewer
