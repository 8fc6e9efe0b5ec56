// The CPU cloud reference against OpenVDB's own vdb_render (libopenvdb-tools) on the same VDB,
// camera and light: isotropic phase, no ambient, vdb_render -gain 0 (single scattering).
//
// vdb_render's model (openvdb/tools/RayTracer.h, VolumeRender): coefficients per voxel (steps in
// index space), so extinction_per_m = (absorb + scatter) / voxel and albedo = scatter / (absorb +
// scatter); -light X,Y,Z is the direction towards the light (the shadow ray's direction); no
// phase function (weight 1 instead of 1 / 4 pi), so its radiance is ours times 4 pi;
// alpha = 1 - mean transmittance; the camera is ours (horizontal fov, pixel centres at +0.5, row 0
// at the top, -lookat/-up frame as glm::lookAt). Its primary samples sit at multiples of -step
// from the eye (second order, like our midpoints), but its shadow samples start one -shadowstep
// away from the point (a right-endpoint sum), which underestimates the shadow optical depth by
// about shadowstep/2 * sigma * rho: hence the small -shadowstep below. Its ray intersector
// (VolumeRayIntersector, no dilation) marches only through existing 8^3 leaf nodes, each taken as
// the index box [origin, origin + 8): the trilinear ramp within one voxel below the low face of
// an absent leaf is skipped (alpha up to 0.027 too low at such silhouettes in a sparse grid), so
// the test grid keeps every voxel of its box active (zeros included) and every leaf exists.
//
// The grid is the bench's noisy sphere at 32^3 (nimbus::app, bench_clouds_scene.hpp), run through
// the bench's vdb_render runner. Measured (64x48, -step 0.25 -shadowstep 0.1; ours 0.25 / 0.25
// voxel): alpha max |diff| 4.6e-4, RMSE 7.9e-5 over covered pixels; radiance * 4 pi relative RMSE
// 0.70 %, mean bias +0.65 % (vdb_render brighter: the shadow bias above).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "nimbus/app/bench_clouds_scene.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "support/vdb_fixtures.hpp"

namespace nr = nimbus::render;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kVdbRender = "/usr/bin/vdb_render";

}  // namespace

TEST(CloudVdbRender, ReferenceMatchesVdbRender) {
  ASSERT_TRUE(std::filesystem::exists(kVdbRender))
      << kVdbRender << " is missing: install the Debian package libopenvdb-tools (scripts/install-deps.sh)";
  nimbus::test::TempDir dir;
  // The bench's noisy sphere (nimbus::app) at 32^3: fBm ripples on a radial ramp, every voxel of
  // its box active.
  const auto grid = nimbus::app::bench_noisy_sphere(32);
  openvdb::io::File((dir / "sphere.vdb").string()).write(openvdb::GridCPtrVec{grid});

  nr::Camera camera;
  camera.eye = {0.3, 0.4, 1.3};
  camera.look_at = {0.02, -0.03, 0.01};
  camera.up = {0.1, 1.0, 0.0};
  camera.fov_deg = 40.0;
  camera.width = 64;
  camera.height = 48;
  const glm::dvec3 to_light{0.6, 0.8, 0.3};
  nimbus::app::VdbRenderSettings vr;
  vr.absorb_per_voxel = 0.02;
  vr.scatter_per_voxel = 0.2;
  vr.step = 0.25;
  vr.shadow_step = 0.1;
  vr.cutoff = 1e-9;
  vr.cpus = 1;
  const nimbus::app::VdbRenderRun run =
      nimbus::app::run_vdb_render(kVdbRender, dir / "sphere.vdb", dir / "vdb.exr", camera, to_light, vr);
  const nr::Image& vdb = run.image;
  ASSERT_EQ(vdb.width, camera.width);
  ASSERT_EQ(vdb.height, camera.height);

  const double voxel = grid->voxelSize()[0];
  const std::vector<nr::CloudVolume> clouds = {
      nr::make_cloud_volume(*grid, nimbus::app::vdb_render_optics(vr, voxel), "sphere")};
  nr::Light light;
  light.direction_to_sun = to_light;
  light.irradiance_w_m2 = glm::dvec3(1.0);
  nr::CloudReferenceSettings settings;
  settings.view_step_voxels = 0.25;
  settings.shadow_step_voxels = 0.25;
  const nr::Image ours = nr::render_cloud_reference(clouds, camera, light, settings);

  // Alpha over the covered pixels (ours > 0.01), and its worst pixel anywhere.
  double max_abs = 0.0, sum_sq = 0.0;
  int covered = 0;
  nr::Image scaled = vdb;  // vdb_render's radiance / 4 pi: our normalised isotropic phase
  for (int y = 0; y < vdb.height; ++y)
    for (int x = 0; x < vdb.width; ++x) {
      const double a = ours.pixel(x, y)[3], b = vdb.pixel(x, y)[3];
      max_abs = std::max(max_abs, std::abs(a - b));
      if (a > 0.01) {
        sum_sq += (a - b) * (a - b);
        ++covered;
      }
      for (int c = 0; c < 3; ++c) scaled.pixel(x, y)[c] = float(vdb.pixel(x, y)[c] / (4.0 * kPi));
    }
  ASSERT_GT(covered, vdb.width * vdb.height / 4);
  const double rmse = std::sqrt(sum_sq / covered);
  const nr::ImageError e = nr::compare_images(scaled, ours);
  std::cout << "alpha max " << max_abs << " rmse " << rmse << "; radiance rel_rmse " << e.rel_rmse << " bias "
            << e.mean_bias << " max_rel " << e.max_rel << " over " << e.pixels << " px\n";
  EXPECT_LT(max_abs, 0.003);
  EXPECT_LT(rmse, 5e-4);
  EXPECT_LT(e.rel_rmse, 0.015);
  EXPECT_GT(e.mean_bias, 0.0);  // vdb_render's shorter shadow paths make it brighter, never darker
  EXPECT_LT(e.mean_bias, 0.012);
}
