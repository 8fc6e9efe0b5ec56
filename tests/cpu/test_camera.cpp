// Camera: validation messages, the pixel-centre rays and the GL matrices that must put each
// pixel's ray exactly at that pixel's centre (row 0 = top, GL window y flipped).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/camera.hpp"

namespace nr = nimbus::render;

namespace {

nr::Camera tilted_camera() {
  nr::Camera c;
  c.eye = {1.0, 2.0, 3.0};
  c.look_at = {-4.0, 0.5, -7.0};
  c.up = {0.2, 1.0, 0.1};  // not orthogonal to the view direction
  c.fov_deg = 70.0;
  c.width = 64;
  c.height = 36;
  c.near_m = 0.1;
  c.far_m = 500.0;
  return c;
}

void expect_error_naming(const nr::Camera& c, const std::string& field) {
  try {
    nr::validate(c);
    FAIL() << "no error for a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

TEST(Camera, ValidationNamesTheField) {
  EXPECT_NO_THROW(nr::validate(tilted_camera()));
  nr::Camera c = tilted_camera();
  c.look_at = c.eye;
  expect_error_naming(c, "look_at");
  c = tilted_camera();
  c.up = c.look_at - c.eye;
  expect_error_naming(c, "up");
  c.up = {0.0, 0.0, 0.0};
  expect_error_naming(c, "up");
  for (const double fov : {0.0, 180.0, -10.0, std::nan("")}) {
    c = tilted_camera();
    c.fov_deg = fov;
    expect_error_naming(c, "fov_deg");
  }
  c = tilted_camera();
  c.width = 0;
  expect_error_naming(c, "width");
  c = tilted_camera();
  c.height = -3;
  expect_error_naming(c, "height");
  c = tilted_camera();
  c.eye.x = INFINITY;
  expect_error_naming(c, "eye");
  c = tilted_camera();
  c.near_m = 0.0;
  expect_error_naming(c, "near_m");
  c = tilted_camera();
  c.far_m = c.near_m;
  expect_error_naming(c, "far_m");
  for (const glm::dvec2 o : {glm::dvec2(1.01, 0.0), glm::dvec2(0.0, -1.5), glm::dvec2(std::nan(""), 0.0)}) {
    c = tilted_camera();
    c.pixel_offset = o;
    expect_error_naming(c, "pixel_offset");
  }
  c = tilted_camera();
  c.pixel_offset = {-1.0, 1.0};
  EXPECT_NO_THROW(nr::validate(c));
}

TEST(Camera, FrameIsOrthonormalAndRightHanded) {
  const nr::Camera c = tilted_camera();
  const nr::CameraFrame f = nr::camera_frame(c);
  EXPECT_NEAR(glm::length(f.right), 1.0, 1e-15);
  EXPECT_NEAR(glm::length(f.up), 1.0, 1e-15);
  EXPECT_NEAR(glm::length(f.forward), 1.0, 1e-15);
  EXPECT_NEAR(glm::dot(f.right, f.up), 0.0, 1e-15);
  EXPECT_NEAR(glm::dot(f.right, f.forward), 0.0, 1e-15);
  EXPECT_NEAR(glm::dot(f.up, f.forward), 0.0, 1e-15);
  // GL camera space: x right, y up, z backward.
  EXPECT_NEAR(glm::length(glm::cross(f.right, f.up) + f.forward), 0.0, 1e-15);
  EXPECT_GT(glm::dot(f.up, c.up), 0.0);
  EXPECT_NEAR(angle_between(f.forward, c.look_at - c.eye), 0.0, 1e-15);
}

TEST(Camera, CentreOfTheImageLooksAtLookAt) {
  for (const auto& [w, h] : {std::pair{64, 36}, std::pair{33, 19}}) {
    nr::Camera c = tilted_camera();
    c.width = w;
    c.height = h;
    // The continuous image centre; for odd sizes that is the centre of pixel (w/2, h/2).
    const glm::dvec3 d = nr::pixel_ray(c, 0.5 * (w - 1), 0.5 * (h - 1));
    EXPECT_NEAR(angle_between(d, c.look_at - c.eye), 0.0, 1e-14) << w << "x" << h;
  }
}

TEST(Camera, HorizontalFieldOfViewAndAspect) {
  const nr::Camera c = tilted_camera();
  const nr::CameraFrame f = nr::camera_frame(c);
  const double half = 0.5 * c.fov_deg * M_PI / 180.0;
  const double cy = 0.5 * (c.height - 1), cx = 0.5 * (c.width - 1);
  // Left and right image edges (x = -0.5 and x = width - 0.5 are pixel-centre coordinates of
  // the edges) make fov/2 with forward; the top edge makes atan(tan(fov/2) h / w).
  EXPECT_NEAR(angle_between(nr::pixel_ray(c, -0.5, cy), f.forward), half, 1e-14);
  EXPECT_NEAR(angle_between(nr::pixel_ray(c, c.width - 0.5, cy), f.forward), half, 1e-14);
  const double vhalf = std::atan(std::tan(half) * c.height / c.width);
  EXPECT_NEAR(angle_between(nr::pixel_ray(c, cx, -0.5), f.forward), vhalf, 1e-14);
  // Row 0 is the top: it leans toward up; column 0 is the left: it leans away from right.
  EXPECT_GT(glm::dot(nr::pixel_ray(c, cx, 0), f.up), 0.0);
  EXPECT_LT(glm::dot(nr::pixel_ray(c, 0, cy), f.right), 0.0);
  EXPECT_NEAR(glm::length(nr::pixel_ray(c, 3, 5)), 1.0, 1e-15);
}

TEST(Camera, PixelOffsetMovesEveryRayAcrossTheImagePlane) {
  nr::Camera c = tilted_camera();
  const nr::Camera centred = c;
  c.pixel_offset = {0.375, -0.625};
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{63, 35}, std::pair{17, 22}}) {
    const glm::dvec3 moved = nr::pixel_ray(c, x, y);
    const glm::dvec3 expected = nr::pixel_ray(centred, x + 0.375, y - 0.625);
    EXPECT_NEAR(angle_between(moved, expected), 0.0, 1e-14) << x << "," << y;
    EXPECT_GT(angle_between(moved, nr::pixel_ray(centred, x, y)), 1e-4);
  }
}

TEST(Camera, ProjectionPutsEachPixelRayAtItsPixelCentre) {
  for (const glm::dvec2 offset : {glm::dvec2(0.0), glm::dvec2(0.43, -0.91)}) {
  nr::Camera c = tilted_camera();
  c.pixel_offset = offset;
  const glm::dmat4 vp = nr::projection_matrix(c) * nr::view_matrix(c);
  for (int y = 0; y < c.height; y += 7) {
    for (int x = 0; x < c.width; x += 9) {
      for (const double s : {0.2, 3.0, 120.0}) {
        const glm::dvec3 p = c.eye + s * nr::pixel_ray(c, x, y);
        const glm::dvec4 clip = vp * glm::dvec4(p, 1.0);
        ASSERT_GT(clip.w, 0.0);
        const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
        // GL viewport (0, 0, w, h): window = (ndc + 1) / 2 * size, origin bottom-left.
        const double wx = 0.5 * (ndc.x + 1.0) * c.width, wy = 0.5 * (ndc.y + 1.0) * c.height;
        EXPECT_NEAR(wx, x + 0.5, 1e-9);
        EXPECT_NEAR(wy, c.height - (y + 0.5), 1e-9) << "GL row h-1-y holds image row y";
        EXPECT_GT(ndc.z, -1.0);
        EXPECT_LT(ndc.z, 1.0);
      }
    }
  }
  }
}

TEST(Camera, DepthRangeMapsNearAndFarPlanes) {
  const nr::Camera c = tilted_camera();
  const glm::dmat4 vp = nr::projection_matrix(c) * nr::view_matrix(c);
  const glm::dvec3 fwd = nr::camera_frame(c).forward;
  auto ndc_z = [&](double dist) {
    const glm::dvec4 clip = vp * glm::dvec4(c.eye + dist * fwd, 1.0);
    return clip.z / clip.w;
  };
  EXPECT_NEAR(ndc_z(c.near_m), -1.0, 1e-12);
  EXPECT_NEAR(ndc_z(c.far_m), 1.0, 1e-12);
  // The view matrix takes the eye to the origin and forward to -z.
  const glm::dvec4 e = nr::view_matrix(c) * glm::dvec4(c.eye, 1.0);
  EXPECT_NEAR(glm::length(glm::dvec3(e)), 0.0, 1e-12);
  const glm::dvec4 f = nr::view_matrix(c) * glm::dvec4(fwd, 0.0);
  EXPECT_NEAR(f.z, -1.0, 1e-15);
}
