// Small clouds, cameras and GL textures for the half-angle slicer's tests (test_cloud_slices*.cpp).
#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"

namespace nimbus::render::slice_test {

// An n^3 grid of voxel edge voxel_m centred on `centre`: voxel (i, j, k) at centre +
// voxel_m (i - (n-1)/2, j - (n-1)/2, k - (n-1)/2), every voxel active with density(i, j, k).
inline CloudVolume cube_cloud(int n, double voxel_m, const std::function<float(int, int, int)>& density,
                              const CloudOptics& optics, const glm::dvec3& centre = glm::dvec3(0.0),
                              const std::string& name = "test") {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_m));
  const double half = 0.5 * (n - 1) * voxel_m;
  grid->transform().postTranslate(openvdb::Vec3d(centre.x - half, centre.y - half, centre.z - half));
  auto acc = grid->getAccessor();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) acc.setValue(openvdb::Coord(i, j, k), density(i, j, k));
  return make_cloud_volume(*grid, optics, name);
}

// The CPU reference's steps for the slicer's tests: a quarter voxel along the view, half toward the light.
inline CloudReferenceSettings quick_reference() {
  CloudReferenceSettings r;
  r.view_step_voxels = 0.25;
  r.shadow_step_voxels = 0.5;
  return r;
}

inline CloudOptics grey_optics(double extinction_per_m, double albedo = 0.9) {
  CloudOptics o;
  o.extinction_per_m = extinction_per_m;
  o.albedo = glm::dvec3(albedo);
  return o;
}

// A smooth lumpy ball in a 24^3 grid of 1/24 m voxels: density in [0, 1], zero at the edges.
inline float lumpy_ball(int i, int j, int k, int n = 24) {
  const double c = 0.5 * (n - 1);
  const double x = (i - c) / n, y = (j - c) / n, z = (k - c) / n;  // metres for a 1 m cube
  const double r = std::sqrt(x * x + y * y + z * z);
  const double lumps = 0.5 * std::sin(11.0 * x + 1.0) * std::sin(9.0 * y + 2.0) * std::sin(13.0 * z + 0.5);
  const double v = 2.5 * (0.42 - r) / 0.42 + lumps;
  return static_cast<float>(std::clamp(v, 0.0, 1.0) * (r < 0.45 ? 1.0 : 0.0));
}

// A camera at `eye` looking at the origin (y up unless the view is vertical).
inline Camera look_at_origin(const glm::dvec3& eye, int size = 64, double fov_deg = 40.0) {
  Camera c;
  c.eye = eye;
  c.look_at = glm::dvec3(0.0);
  const glm::dvec3 v = glm::normalize(-eye);
  c.up = std::abs(v.y) > 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  c.fov_deg = fov_deg;
  c.width = size;
  c.height = size;
  c.near_m = 0.01;
  c.far_m = 100.0;
  return c;
}

// A direction at `angle_deg` from `v` (unit) in the plane of v and `towards`.
inline glm::dvec3 rotate_towards(const glm::dvec3& v, const glm::dvec3& towards, double angle_deg) {
  const glm::dvec3 p = glm::normalize(towards - glm::dot(towards, v) * v);
  const double a = angle_deg * M_PI / 180.0;
  return std::cos(a) * v + std::sin(a) * p;
}

// A camera-sized RGBA32F or R32F texture filled with `values` (row 0 at the BOTTOM, GL order).
inline GlTexture texture_from(GLenum format, int w, int h, const std::vector<float>& values) {
  GlTexture t = make_texture_2d(format, w, h, TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
  glTextureSubImage2D(t.id(), 0, 0, 0, w, h, format == GL_R32F ? GL_RED : GL_RGBA, GL_FLOAT, values.data());
  return t;
}

inline bool all_finite(const Image& img) {
  for (float v : img.rgba)
    if (!std::isfinite(v)) return false;
  return true;
}

// Root-mean-square difference of the RGB channels of two images of the same size.
inline double rms_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = static_cast<double>(a.rgba[i]) - b.rgba[i];
    sum += d * d;
    ++n;
  }
  return std::sqrt(sum / static_cast<double>(n));
}

}  // namespace nimbus::render::slice_test
