// The pinhole camera shared by the GL renderer and the CPU reference: its frame, the ray
// through a pixel centre and the OpenGL matrices that rasterise the same rays.
//
// Conventions (what the GL side must do): pixel (x, y) with y = 0 the TOP row covers
// [x, x+1] x [y, y+1] and its ray goes through (x + 0.5, y + 0.5). With the GL viewport
// (0, 0, w, h), view_matrix and projection_matrix put that ray's points at GL window
// coordinates (x + 0.5, h - (y + 0.5)): GL's window origin is the bottom-left corner, so GL row
// h-1-y is image row y, i.e. an image read back with glReadPixels (bottom row first) must be
// flipped vertically before it is stored as an Image (row 0 = top).
#include "nimbus/render/core/camera.hpp"
#include "nimbus/base/validate.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace nimbus::render {
namespace {

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument("camera " + field + ": " + why);
}

// Half-extents of the image plane at unit distance along forward: tan(fov/2) across the
// width (horizontal field of view) and height/width of that vertically.
struct PlaneHalfExtent {
  double x, y;
};
PlaneHalfExtent half_extent(const Camera& c) {
  const double hx = std::tan(0.5 * c.fov_deg * M_PI / 180.0);
  return {hx, hx * static_cast<double>(c.height) / static_cast<double>(c.width)};
}

}  // namespace

void validate(const Camera& c) {
  if (!finite3(c.eye)) fail("eye", "must be finite");
  if (!finite3(c.look_at)) fail("look_at", "must be finite");
  if (!finite3(c.up)) fail("up", "must be finite");
  const glm::dvec3 view = c.look_at - c.eye;
  const double view_len = glm::length(view);
  if (!(view_len > 0.0)) fail("look_at", "must differ from eye");
  const double up_len = glm::length(c.up);
  if (!(up_len > 0.0)) fail("up", "must be non-zero");
  // The frame needs a right vector: up must not be (nearly) parallel to the view direction.
  const double sin_angle = glm::length(glm::cross(view / view_len, c.up / up_len));
  if (!(sin_angle > 1e-9)) fail("up", "must not be parallel to the view direction (look_at - eye)");
  if (!std::isfinite(c.fov_deg) || !(c.fov_deg > 0.0) || !(c.fov_deg < 180.0)) {
    fail("fov_deg", "must be in (0, 180) degrees, got " + number_text(c.fov_deg));
  }
  if (c.width <= 0) fail("width", "must be > 0, got " + std::to_string(c.width));
  if (c.height <= 0) fail("height", "must be > 0, got " + std::to_string(c.height));
  if (!std::isfinite(c.near_m) || !(c.near_m > 0.0)) fail("near_m", "must be finite and > 0");
  if (!std::isfinite(c.far_m) || !(c.far_m > c.near_m)) fail("far_m", "must be finite and > near_m");
  if (!(std::abs(c.pixel_offset.x) <= 1.0) || !(std::abs(c.pixel_offset.y) <= 1.0))
    fail("pixel_offset", "must be finite and within [-1, 1] pixels on each axis");
}

CameraFrame camera_frame(const Camera& c) {
  // Same construction as glm::lookAt, so view_matrix rotates world into exactly this frame.
  const glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
  const glm::dvec3 up = glm::cross(right, forward);
  return {right, up, forward};
}

glm::dvec3 pixel_ray(const Camera& c, double x, double y) {
  const CameraFrame f = camera_frame(c);
  const PlaneHalfExtent e = half_extent(c);
  // Normalised device coordinates of the pixel centre, y up (row 0 is the top).
  const double ndc_x = 2.0 * (x + 0.5 + c.pixel_offset.x) / c.width - 1.0;
  const double ndc_y = 1.0 - 2.0 * (y + 0.5 + c.pixel_offset.y) / c.height;
  return glm::normalize(f.forward + (ndc_x * e.x) * f.right + (ndc_y * e.y) * f.up);
}

glm::dmat4 view_matrix(const Camera& c) { return glm::lookAtRH(c.eye, c.look_at, c.up); }

glm::dmat4 projection_matrix(const Camera& c) {
  // The frustum whose near-plane rectangle is the image plane scaled by near_m, shifted by
  // pixel_offset (a pixel is 2 e.x n / width across on the near plane; image y runs down, the
  // frustum's up); the usual GL depth mapping of [-near, -far] (view z) onto NDC z in [-1, 1].
  const PlaneHalfExtent e = half_extent(c);
  const double n = c.near_m, f = c.far_m;
  const double sx = 2.0 * n * e.x * c.pixel_offset.x / c.width;
  const double sy = -2.0 * n * e.y * c.pixel_offset.y / c.height;
  return glm::frustumRH_NO(-n * e.x + sx, n * e.x + sx, -n * e.y + sy, n * e.y + sy, n, f);
}

}  // namespace nimbus::render
