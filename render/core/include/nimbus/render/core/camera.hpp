// A pinhole camera with vdb_render's flags (--eye, --look-at, --up, --fov as the horizontal
// field of view), shared by the GL renderer and the CPU reference so both see the same rays.
#pragma once
#include <glm/glm.hpp>

namespace nimbus::render {

struct Camera {
  glm::dvec3 eye{0.0, 1.7, 10.0};     // metres
  glm::dvec3 look_at{0.0, 1.7, 0.0};  // metres
  glm::dvec3 up{0.0, 1.0, 0.0};       // need not be orthogonal to the view direction
  double fov_deg = 60.0;              // horizontal field of view, degrees, in (0, 180)
  int width = 640;                    // pixels
  int height = 360;                   // pixels
  double near_m = 0.05;               // GL near plane, metres (the reference ignores it)
  double far_m = 2000.0;              // GL far plane, metres (the reference ignores it)
  // Every ray moved across the image plane by this many pixels (x right, y down), each in
  // [-1, 1]: the sub-pixel offsets of a still view's progressive samples (progressive_frame.hpp).
  glm::dvec2 pixel_offset{0.0, 0.0};
};

// Throws std::invalid_argument naming the field when the camera is unusable (eye == look_at,
// up parallel to the view direction, fov outside (0, 180), size <= 0, non-finite values).
void validate(const Camera& camera);

// Orthonormal camera frame: right, up, forward (forward points from eye to look_at).
struct CameraFrame {
  glm::dvec3 right, up, forward;
};
CameraFrame camera_frame(const Camera& camera);

// Unit direction of the ray through the centre of pixel (x, y), moved by pixel_offset; y = 0 is
// the top row. Pixel (x, y) covers [x, x+1] x [y, y+1]; the image plane spans tan(fov/2)
// horizontally.
glm::dvec3 pixel_ray(const Camera& camera, double x, double y);

// OpenGL matrices (right-handed view, perspective with the camera's near/far planes) that
// put the centre of pixel (x, y) exactly where pixel_ray points (the frustum shifted by
// pixel_offset).
glm::dmat4 view_matrix(const Camera& camera);
glm::dmat4 projection_matrix(const Camera& camera);

}  // namespace nimbus::render
