// The sky scene's ground on the GPU: it reaches the horizon and meets the sky there without a
// band (shaders/lib/far_ground_haze.glsl), and the clouds' shadow on it has the penumbra of the
// sun's disc, as wide as the distance to the occluding cloud times the disc's angle
// (cloud_transmittance_soft, shaders/lib/cloud_shadow.glsl).
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nimbus/render/clouds/cloud_shadow.hpp"
#include "nimbus/render/media/atmosphere.hpp"
#include "nimbus/render/core/pixel_depths.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/gl/volume_texture.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"
#include "test_cloud_slices_support.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

using namespace slice_test;

double luminance(const Image& img, int x, int y) {
  const std::size_t i = 4 * (static_cast<std::size_t>(y) * img.width + x);
  return 0.2126 * img.rgba[i] + 0.7152 * img.rgba[i + 1] + 0.0722 * img.rgba[i + 2];
}

// A level camera 300 m up looking north over the sky scene's ground, with a narrow frame tall
// in pixels, so that several rows lie within a tenth of a degree below the horizon. Its one
// cloud is behind it, its shadow too.
TEST(SkyGround, TheGroundReachesTheHorizonAndMeetsTheSkyThereWithoutABand) {
  NIMBUS_REQUIRE_GL();
  const Scene scene = make_scene("sky");
  const Light light{scene.sun->direction_to_sun, scene.sun->irradiance_w_m2};
  FrameSettings settings;
  settings.slices.slices = 16;
  settings.slices.light_res = 32;
  settings.shafts = parse_shaft_method("raymarch:8");
  settings.cloud_shadow_res = 64;
  FrameRenderer frame(scene, light, settings);
  frame.set_clouds({cube_cloud(8, 25.0, [](int, int, int) { return 0.5f; }, grey_optics(0.05), {0.0, 400.0, 3000.0}, "behind")});
  Camera c;
  c.eye = {0.0, 300.0, 0.0};
  c.look_at = {0.0, 300.0, -100000.0};
  c.fov_deg = 4.0;
  c.width = 32;
  c.height = 480;  // rows 0.125 degrees apart; the horizon between rows 239 and 240
  c.near_m = 1.0;
  c.far_m = 40000.0;
  PixelDepths depths;
  const Image img = frame.render(c, nullptr, &depths);
  const int x = c.width / 2;
  // Every row below the horizon is ground, however far: the first is 275 km away, row 299 2.3 km.
  for (int y = 240; y < 300; ++y) {
    ASSERT_LT(pixel_ray(c, x, y).y, 0.0);
    EXPECT_GT(depths.distance_m(x, y), 0.0f) << "row " << y << " below the horizon shows no ground";
  }
  // The row just below the horizon is the sky just above it, within a few percent.
  const double sky = luminance(img, x, 239), ground = luminance(img, x, 240);
  EXPECT_NEAR(ground / sky, 1.0, 0.04) << "sky " << sky << ", ground " << ground;
  // No band: no row in the first degrees below the horizon is brighter than both the sky at
  // the horizon and the brightest of the near ground (the textured rows 280-299).
  double near_max = 0.0;
  for (int y = 280; y < 300; ++y) near_max = std::max(near_max, luminance(img, x, y));
  for (int y = 240; y < 280; ++y)
    EXPECT_LE(luminance(img, x, y), 1.01 * std::max(sky, near_max)) << "row " << y;
}

// A flat opaque slab of cloud (40 x 4 x 40 voxels of 1 m, tau 20 through it) with the sun
// overhead; a camera looking straight down on the ground under the slab's edge.
struct Penumbra {
  double sd_m;        // standard deviation of the edge's line spread (the profile's derivative)
  double occluder_m;  // height of the slab's middle above the ground
};

Penumbra measure_penumbra(double slab_bottom_m) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
  grid->transform().postTranslate(openvdb::Vec3d(-19.5, slab_bottom_m + 0.5, -19.5));
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0, 0, 0), openvdb::Coord(39, 3, 39)), 10.0f, true);
  CloudOptics optics;
  optics.extinction_per_m = 0.5;
  std::vector<CloudVolume> clouds{make_cloud_volume(*grid, optics, "slab")};
  const VolumeTexture tex = upload_volume(clouds[0].box, *clouds[0].transform, GL_R32F);
  const Light sun{{0.0, 1.0, 0.0}, glm::dvec3{2.0}};
  const CloudShadowMap map = build_cloud_shadow_map(clouds, {&tex}, sun, 2048);

  Scene s;
  s.name = "penumbra-test";
  s.medium.extinction_per_m = 0.0;
  s.sun = sun_light(sun.direction_to_sun, sun.irradiance_w_m2);
  s.ground = GroundPlane{0.0, Material{{0.5, 0.5, 0.5}}};
  ShaftRenderer r(s);
  r.set_cloud_shadow(&map);
  Camera c;
  c.eye = {20.3, 40.0, 0.0};
  c.look_at = {20.3, 0.0, 0.0};
  c.up = {0.0, 0.0, -1.0};
  c.fov_deg = 16.0;  // +-5.6 m across the ground
  c.width = 401;
  c.height = 3;
  c.near_m = 0.1;
  c.far_m = 1000.0;
  const Image img = r.render(c, parse_shaft_method("raymarch:4"));
  // The profile along the middle row, against x on the ground; its derivative's spread.
  std::vector<double> xs, ls;
  for (int i = 0; i < c.width; ++i) {
    const glm::dvec3 d = pixel_ray(c, i, 1);
    xs.push_back(c.eye.x + d.x * (c.eye.y / -d.y));
    ls.push_back(luminance(img, i, 1));
  }
  EXPECT_NEAR(ls.front(), 0.0, 0.01);          // umbra on one side (x < 20)
  EXPECT_NEAR(ls.back(), 1.0 / M_PI, 0.003);   // full sun on the other
  double w = 0.0, m = 0.0, m2 = 0.0;
  for (std::size_t i = 0; i + 1 < ls.size(); ++i) {
    const double dl = std::abs(ls[i + 1] - ls[i]), x = 0.5 * (xs[i] + xs[i + 1]);
    w += dl;
    m += dl * x;
    m2 += dl * x * x;
  }
  m /= w;
  return {std::sqrt(std::max(m2 / w - m * m, 0.0)), slab_bottom_m + 2.0};
}

// A uniform disc of radius R seen through a straight edge spreads it by the disc's chord
// lengths, sqrt(R^2 - x^2), whose standard deviation is R / 2; R = distance x tan(the sun's
// angular radius). The slab's own edge (its trilinear ramp) and the map's texels add a few
// centimetres in quadrature.
TEST(SkyGround, ACloudShadowsPenumbraGrowsWithTheDistanceToTheCloud) {
  NIMBUS_REQUIRE_GL();
  const double tan_r = std::tan(Atmosphere{}.sun_angular_radius_rad);
  const Penumbra low = measure_penumbra(100.0), high = measure_penumbra(400.0);
  for (const Penumbra& p : {low, high})
    EXPECT_NEAR(p.sd_m / (0.5 * p.occluder_m * tan_r), 1.0, 0.2) << "occluder " << p.occluder_m << " m: sd " << p.sd_m;
  EXPECT_NEAR((high.sd_m / low.sd_m) / (high.occluder_m / low.occluder_m), 1.0, 0.15);
}

}  // namespace
}  // namespace nimbus::render
