// The viewer's camera moves on a view state's eye and look_at: orbit with vdb_view's habits
// (left drag tumbles about the target, right drag pans, the wheel zooms), and a fly mode (WASD
// and the mouse). Pure functions, so scripts and tests move the camera exactly as the mouse does.
#pragma once
#include <glm/glm.hpp>

namespace nimbus::viewer {

struct CameraPose {
  glm::dvec3 eye;
  glm::dvec3 look_at;
};

// Left drag by (dx, dy) pixels: yaw about the world's up axis and pitch about the camera's
// right axis, around look_at, 0.3 degrees per pixel; pitch stays within 89 degrees of the horizon.
CameraPose tumble(const CameraPose& pose, double dx_px, double dy_px);
// Right drag: eye and target move together in the view plane, by as many metres as the target's
// distance makes one pixel span (fov_deg horizontal, width_px wide).
CameraPose pan(const CameraPose& pose, double dx_px, double dy_px, double fov_deg, int width_px);
// Wheel: the eye moves towards the target by 10 % per notch (outwards for negative notches),
// keeping 1 m to 200 km between them.
CameraPose zoom(const CameraPose& pose, double notches);
// Fly: the mouse turns the view about the eye (0.2 degrees per pixel), and `move` (right,
// up, forward: each -1, 0 or 1) carries eye and target at speed_m_s for dt_s.
CameraPose fly_look(const CameraPose& pose, double dx_px, double dy_px);
CameraPose fly_move(const CameraPose& pose, const glm::dvec3& move, double speed_m_s, double dt_s);
// The pose with its eye at least min_eye_y high (render y, up): a tumble that would take the eye
// under the ground stops on it (the eye slides up its sphere about the target, keeping its
// distance and heading); where the target is that low too (a pan, a flight) eye and target rise
// together. A pose already high enough is returned as it is.
CameraPose keep_eye_above(const CameraPose& pose, double min_eye_y);

}  // namespace nimbus::viewer
