// Where clouds come from and how a camera is framed on them (render/core cloud_source.hpp,
// cloud_framing.hpp, cloud_method.hpp): a z-up file is turned y-up by its metadata, a y-up one is
// not, and both land where the grid's own transform says; a preset generates the same cloud as
// volume::generate_density; a framed camera sees every corner of the clouds' bounds, and under a
// sky stands on the ground with the horizon in the picture; names round-trip and bad ones are
// refused.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/core/cloud_method.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/vdb_fixtures.hpp"

namespace nimbus::render {
namespace {

// The centre of mass of a cloud's density in world metres.
glm::dvec3 centroid(const CloudVolume& c) {
  glm::dvec3 sum(0.0);
  double mass = 0.0;
  const auto& b = c.box;
  for (int64_t k = 0; k < b.size[2]; ++k)
    for (int64_t j = 0; j < b.size[1]; ++j)
      for (int64_t i = 0; i < b.size[0]; ++i) {
        const double v = b.values[static_cast<std::size_t>(i + b.size[0] * (j + b.size[1] * k))];
        const glm::dvec3 idx(double(b.origin[0] + i), double(b.origin[1] + j), double(b.origin[2] + k));
        sum += v * glm::dvec3(c.index_to_world * glm::dvec4(idx, 1.0));
        mass += v;
      }
  return sum / mass;
}

TEST(CloudSource, AZUpFileIsTurnedYUpAndAYUpFileIsNot) {
  openvdb::initialize();
  test::TempDir dir;
  // A ball around index (0, 0, 0), moved so that its centre is at world (1, 2, 3) in the file.
  auto ball = test::make_ball(6, 0.5);
  ball->transform().postTranslate(openvdb::Vec3d(1.0, 2.0, 3.0));
  volume::ExportInfo z_up;  // nimbus's own files are z-up
  volume::write_volume_vdb(dir / "z.vdb", {ball}, z_up);
  const CloudVolume z = load_cloud_file((dir / "z.vdb").string(), "", UpAxis::Auto, CloudOptics{});
  const CloudVolume y = load_cloud_file((dir / "z.vdb").string(), "", UpAxis::Y, CloudOptics{});
  EXPECT_EQ(z.name, (dir / "z.vdb").string());
  // Taken as it is (forced y), the ball sits where the file's transform puts it, near (1, 2, 3) ...
  const glm::dvec3 cy = centroid(y), cz = centroid(z);
  EXPECT_LT(glm::length(cy - glm::dvec3(1.0, 2.0, 3.0)), 0.25);
  // ... and turned y-up by the file's up_axis, (x, y, z) becomes (x, z, -y).
  EXPECT_NEAR(cz.x, cy.x, 1e-9);
  EXPECT_NEAR(cz.y, cy.z, 1e-9);
  EXPECT_NEAR(cz.z, -cy.y, 1e-9);
  EXPECT_EQ(load_cloud_file((dir / "z.vdb").string(), "", UpAxis::Z, CloudOptics{}).box.values, z.box.values);
  EXPECT_THROW(load_cloud_file((dir / "z.vdb").string(), "no_such_grid", UpAxis::Auto, CloudOptics{}),
               volume::GridNotFound);
  EXPECT_THROW(load_cloud_file((dir / "missing.vdb").string(), "", UpAxis::Auto, CloudOptics{}), std::runtime_error);
}

TEST(CloudSource, APresetIsTheGeneratedDensityTurnedYUp) {
  const PresetCloud preset = load_preset_cloud("steam");
  EXPECT_EQ(preset.name, "steam");
  EXPECT_GT(preset.voxel_size_m, 0.0);
  const double voxel = 0.02;
  const CloudVolume cloud = generate_preset_cloud(preset, voxel, 0.5, CloudOptics{});
  volume::GenerateOptions opt;
  opt.voxel_size = voxel;
  opt.time = 0.5;
  const auto grid = volume::rotate_z_up_to_y_up(*volume::generate_density(preset.params, opt));
  const CloudVolume direct = make_cloud_volume(*grid, CloudOptics{}, "steam");
  EXPECT_EQ(cloud.box.values, direct.box.values);
  EXPECT_EQ(cloud.world_min, direct.world_min);
  EXPECT_THROW(load_preset_cloud("no-such-cloud"), std::invalid_argument);
}

TEST(CloudSource, NamesRoundTripAndBadOnesAreRefused) {
  for (CloudMethod m : {CloudMethod::Slices, CloudMethod::Reference}) EXPECT_EQ(parse_cloud_method(to_string(m)), m);
  EXPECT_THROW(parse_cloud_method("raymarch:8"), std::invalid_argument);
  EXPECT_EQ(parse_up_axis("auto"), UpAxis::Auto);
  EXPECT_EQ(parse_up_axis("y"), UpAxis::Y);
  EXPECT_EQ(parse_up_axis("z"), UpAxis::Z);
  EXPECT_THROW(parse_up_axis("x"), std::invalid_argument);
}

// Projects a world point to normalised device coordinates of `cam` (x, y in [-1, 1] on screen).
glm::dvec3 ndc(const Camera& cam, const glm::dvec3& p) {
  const glm::dvec4 clip = projection_matrix(cam) * view_matrix(cam) * glm::dvec4(p, 1.0);
  return glm::dvec3(clip) / clip.w;
}

TEST(CloudFraming, TheFramedCameraSeesEveryCornerOfTheClouds) {
  openvdb::initialize();
  auto ball = test::make_ball(10, 20.0);
  ball->transform().postTranslate(openvdb::Vec3d(300.0, 900.0, -200.0));
  const std::vector<CloudVolume> clouds = {make_cloud_volume(*ball, CloudOptics{}, "ball")};
  Camera base;
  base.width = 320;
  base.height = 180;
  for (bool on_ground : {false, true}) {
    const Camera c = frame_clouds(base, clouds, on_ground);
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p(k & 1 ? clouds[0].world_max.x : clouds[0].world_min.x,
                         k & 2 ? clouds[0].world_max.y : clouds[0].world_min.y,
                         k & 4 ? clouds[0].world_max.z : clouds[0].world_min.z);
      const glm::dvec3 q = ndc(c, p);
      EXPECT_LE(std::abs(q.x), 1.0) << "corner " << k << " on_ground " << on_ground;
      EXPECT_LE(std::abs(q.y), 1.0) << "corner " << k << " on_ground " << on_ground;
      EXPECT_LT(q.z, 1.0) << "corner " << k << " beyond the far plane";
    }
    if (on_ground) {
      EXPECT_DOUBLE_EQ(c.eye.y, 2.0);
      // The horizon (a far point at eye height straight ahead) is in the picture.
      const glm::dvec3 ahead = c.look_at - c.eye;
      const glm::dvec3 horizon = c.eye + 1e4 * glm::normalize(glm::dvec3(ahead.x, 0.0, ahead.z));
      EXPECT_LE(std::abs(ndc(c, horizon).y), 1.0);
    }
  }
  EXPECT_EQ(frame_clouds(base, {}, true).eye, base.eye);  // nothing to frame
}

// The viewer's G with its panel over the left of the picture: the clouds are framed in the part
// to its right, their centre in the middle of that part, every corner inside it.
TEST(CloudFraming, FramedRightOfACoveredStripTheCloudsFillTheFreePart) {
  openvdb::initialize();
  auto ball = test::make_ball(10, 20.0);
  ball->transform().postTranslate(openvdb::Vec3d(300.0, 900.0, -200.0));
  const std::vector<CloudVolume> clouds = {make_cloud_volume(*ball, CloudOptics{}, "ball")};
  Camera base;
  base.width = 960;
  base.height = 540;
  base.fov_deg = 60.0;
  for (const double covered : {240.0, 480.0}) {
    const double left = -1.0 + 2.0 * covered / base.width;  // the free part in NDC: [left, 1]
    for (bool on_ground : {false, true}) {
      const Camera c = frame_clouds_right_of(base, clouds, on_ground, covered);
      EXPECT_EQ(c.width, base.width);
      EXPECT_EQ(c.fov_deg, base.fov_deg);
      const glm::dvec3 centre = 0.5 * (clouds[0].world_min + clouds[0].world_max);
      EXPECT_NEAR(ndc(c, centre).x, 0.5 * (left + 1.0), on_ground ? 0.05 : 0.01) << covered << " " << on_ground;
      for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p(k & 1 ? clouds[0].world_max.x : clouds[0].world_min.x,
                           k & 2 ? clouds[0].world_max.y : clouds[0].world_min.y,
                           k & 4 ? clouds[0].world_max.z : clouds[0].world_min.z);
        const glm::dvec3 q = ndc(c, p);
        EXPECT_GE(q.x, left) << "corner " << k << " behind the panel, covered " << covered << " on_ground " << on_ground;
        EXPECT_LE(q.x, 1.0) << "corner " << k;
        EXPECT_LE(std::abs(q.y), 1.0) << "corner " << k;
      }
    }
  }
  // Nothing covered: frame_clouds itself.
  EXPECT_EQ(frame_clouds_right_of(base, clouds, false, 0.0).look_at, frame_clouds(base, clouds, false).look_at);
  EXPECT_EQ(frame_clouds_right_of(base, clouds, false, std::nan("")).look_at, frame_clouds(base, clouds, false).look_at);
}

TEST(CloudFraming, AHandPlacedCameraReachesTheFarthestCloud) {
  openvdb::initialize();
  auto ball = test::make_ball(10, 20.0);
  ball->transform().postTranslate(openvdb::Vec3d(0.0, 0.0, -9000.0));
  const std::vector<CloudVolume> clouds = {make_cloud_volume(*ball, CloudOptics{}, "far")};
  Camera c;
  c.far_m = 100.0;
  const Camera fitted = fit_far_plane(c, clouds);
  EXPECT_GT(fitted.far_m, glm::length(clouds[0].world_max - c.eye));
  EXPECT_EQ(fitted.eye, c.eye);
}

}  // namespace
}  // namespace nimbus::render
