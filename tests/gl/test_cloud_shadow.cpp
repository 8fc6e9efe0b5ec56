// The clouds' shadow in the scene (cloud_shadow.hpp, lib/cloud_shadow.glsl): a homogeneous box
// cloud darkens the ground below it by exactly its optical depth, and the fog's ray-marched
// shafts under it by the integral of its transmittance along the view ray.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <cmath>

#include "nimbus/render/clouds/cloud_shadow.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"
#include "nimbus/render/gl/volume_texture.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// n^3 voxels of density rho, 1 m voxels, centres at (i - n/2 + 0.5, y0 + j + 0.5, k - n/2 + 0.5).
CloudVolume box_cloud(int n, float rho, double y0, double sigma_per_m) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
  grid->transform().postTranslate(openvdb::Vec3d(-n / 2.0 + 0.5, y0 + 0.5, -n / 2.0 + 0.5));
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(n - 1)), rho, true);
  CloudOptics optics;
  optics.extinction_per_m = sigma_per_m;
  return make_cloud_volume(*grid, optics, "box");
}

Scene sun_scene(double fog_per_m) {
  Scene s;
  s.name = "cloud-shadow-test";
  s.medium.extinction_per_m = fog_per_m;
  s.medium.albedo = 1.0;
  s.sun = sun_light({0.0, 1.0, 0.0}, glm::dvec3{2.0});
  return s;
}

Camera camera(glm::dvec3 eye, glm::dvec3 at) {
  Camera c;
  c.eye = eye;
  c.look_at = at;
  c.up = {0, 0, -1};
  if (std::abs(glm::normalize(at - eye).z) > 0.9) c.up = {0, 1, 0};
  c.fov_deg = 10.0;
  c.width = c.height = 33;  // odd: the middle pixel's ray is the view direction
  c.near_m = 0.1;
  c.far_m = 1000.0;
  return c;
}

glm::dvec3 middle(const Image& img) {
  const std::size_t i = 4 * (static_cast<std::size_t>(img.height / 2) * img.width + img.width / 2);
  return {img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]};
}

TEST(CloudShadow, ACloudDarkensTheGroundBelowItByItsOpticalDepth) {
  NIMBUS_REQUIRE_GL();
  const int n = 10;
  const double sigma = 0.5, rho = 0.1;
  std::vector<CloudVolume> clouds{box_cloud(n, static_cast<float>(rho), 10.0, sigma)};
  const VolumeTexture tex = upload_volume(clouds[0].box, *clouds[0].transform, GL_R32F);
  const Light light{{0.0, 1.0, 0.0}, glm::dvec3{2.0}};
  const CloudShadowMap map = build_cloud_shadow_map(clouds, {&tex}, light, 128);
  EXPECT_GE(map.top_y_m, 20.0);

  Scene s = sun_scene(0.0);
  s.ground = GroundPlane{0.0, Material{{0.5, 0.5, 0.5}}};
  ShaftRenderer r(s);
  r.set_cloud_shadow(&map);
  const ShaftMethod m = parse_shaft_method("raymarch:4");
  const glm::dvec3 under = middle(r.render(camera({0, 2, 12}, {0, 0, 0}), m));
  const glm::dvec3 beside = middle(r.render(camera({30, 2, 12}, {30, 0, 0}), m));
  // Lambertian ground in full sun: albedo / pi * E; under the box: times e^-(sigma rho n h)
  // (an axis-aligned ray through the trilinear box meets exactly n voxels' worth of density).
  EXPECT_NEAR(beside.x, 0.5 / kPi * 2.0, 1e-4);
  EXPECT_NEAR(under.x / beside.x, std::exp(-sigma * rho * n), 2e-3);
  r.set_cloud_shadow(nullptr);
  EXPECT_NEAR(middle(r.render(camera({0, 2, 12}, {0, 0, 0}), m)).x, beside.x, 1e-4);
}

// Optical depth of the box's column at horizontal offset x (metres) from its axis: the
// trilinear profile is flat between the outer voxel centres and falls linearly to 0 one voxel
// beyond them.
double column_weight(double x, int n) {
  const double inner = n / 2.0 - 0.5;
  const double a = std::abs(x);
  return a <= inner ? 1.0 : std::max(0.0, 1.0 - (a - inner));
}

TEST(CloudShadow, ACloudShadowsTheFogShaftsUnderIt) {
  NIMBUS_REQUIRE_GL();
  const int n = 10;
  const double sigma = 0.5, rho = 0.2, fog = 0.01, E = 2.0;
  std::vector<CloudVolume> clouds{box_cloud(n, static_cast<float>(rho), 10.0, sigma)};
  const VolumeTexture tex = upload_volume(clouds[0].box, *clouds[0].transform, GL_R32F);
  const CloudShadowMap map = build_cloud_shadow_map(clouds, {&tex}, Light{{0.0, 1.0, 0.0}, glm::dvec3{E}}, 256);

  Scene s = sun_scene(fog);
  s.boxes.push_back(Box{{20.0, 0.0, -5.0}, {21.0, 4.0, 5.0}, Material{{0.0, 0.0, 0.0}}});  // ends the ray at t = 60
  ShaftRenderer r(s);
  r.set_cloud_shadow(&map);
  const Camera c = camera({-40, 2, 0}, {0, 2, 0});
  const double shaded = middle(r.render(c, parse_shaft_method("raymarch:512"))).x;

  // Double-precision airlight along the ray: sigma_s p E T_cloud(x) e^(-sigma t), isotropic p.
  const double tau0 = sigma * rho * n;
  double expected = 0.0, open = 0.0;
  const int steps = 600000;
  const double h = 60.0 / steps;
  for (int k = 0; k < steps; ++k) {
    const double t = (k + 0.5) * h;
    const double base = fog / (4.0 * kPi) * E * std::exp(-fog * t) * h;
    open += base;
    expected += base * std::exp(-tau0 * column_weight(-40.0 + t, n));
  }
  ASSERT_LT(expected, 0.95 * open);  // the shadow is a real part of the shaft
  EXPECT_NEAR(shaded / expected, 1.0, 5e-3);
}

}  // namespace
}  // namespace nimbus::render
