// Which copies of a periodic tile the slicer draws (render/core cloud_tiles.hpp): none without a
// reach; with one, whole periods only, each copy once, the far ones within reach, in view and
// outside the near region, and every copy in view and in reach drawn; bad periods refused.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "nimbus/render/core/cloud_tiles.hpp"

namespace nimbus::render {
namespace {

// A tile of n x 4 x n voxels of 10 m (every voxel 1), its corner voxel centred at `corner`, with
// period n voxels along x and z (0: none).
CloudVolume tile(int n, const glm::dvec3& corner, bool periodic, const std::string& name = "tile") {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(10.0));
  grid->transform().postTranslate(openvdb::Vec3d(corner.x, corner.y, corner.z));
  auto acc = grid->getAccessor();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < n; ++i) acc.setValue(openvdb::Coord(i, j, k), 1.0f);
  CloudVolume c = make_cloud_volume(*grid, CloudOptics{}, name);
  if (periodic) c.period_m = glm::dvec3(10.0 * n, 0.0, 10.0 * n);
  return c;
}

// The eye 60 m below a layer at y 0 to 30 m, looking toward -z and up a little, as a sky's camera
// looks at its clouds.
Camera sky_camera() {
  Camera c;
  c.eye = glm::dvec3(37.0, -60.0, 12.0);
  c.look_at = glm::dvec3(37.0, 40.0, -1000.0);
  c.up = glm::dvec3(0.0, 1.0, 0.0);
  c.fov_deg = 70.0;
  c.width = 320;
  c.height = 180;
  c.near_m = 1.0;
  c.far_m = 1e5;
  return c;
}

using Key = std::tuple<std::size_t, long, long>;
Key key(const CloudInstance& i, const CloudVolume& c) {
  return {i.cloud, std::lround(i.offset_m.x / (c.period_m.x > 0 ? c.period_m.x : 1.0)),
          std::lround(i.offset_m.z / (c.period_m.z > 0 ? c.period_m.z : 1.0))};
}

TEST(CloudTiles, WithoutReachEveryCloudIsDrawnWhereItIs) {
  const std::vector<CloudVolume> clouds = {tile(10, {0, 0, 0}, true), tile(4, {500, 0, 0}, false, "lone")};
  for (const double reach : {0.0, 2000.0}) {
    const std::vector<CloudVolume> drawn = reach > 0.0 ? std::vector<CloudVolume>{clouds[1]} : clouds;
    const CloudTilePlan plan = plan_cloud_tiles(drawn, sky_camera(), reach);
    ASSERT_EQ(plan.near.size(), drawn.size());
    for (std::size_t j = 0; j < drawn.size(); ++j) {
      EXPECT_EQ(plan.near[j].cloud, j);
      EXPECT_EQ(plan.near[j].offset_m, glm::dvec3(0.0));
    }
    EXPECT_TRUE(plan.far.empty());
  }
}

TEST(CloudTiles, CopiesFillTheReachOnceEachOutsideTheNearRegion) {
  const int n = 10;  // a 100 m tile
  const std::vector<CloudVolume> clouds = {tile(n, {-45, 0, -45}, true)};
  const CloudVolume& c = clouds[0];
  const Camera cam = sky_camera();
  const double reach = 1500.0;
  const CloudTilePlan plan = plan_cloud_tiles(clouds, cam, reach);
  ASSERT_FALSE(plan.near.empty());
  // The eye's copy first: its tile lies under the eye.
  const glm::dvec3 lo0 = c.world_min + plan.near[0].offset_m, hi0 = c.world_max + plan.near[0].offset_m;
  EXPECT_TRUE(cam.eye.x >= lo0.x && cam.eye.x <= hi0.x && cam.eye.z >= lo0.z && cam.eye.z <= hi0.z);
  std::set<Key> seen;
  double nx0 = 1e300, nx1 = -1e300, nz0 = 1e300, nz1 = -1e300;
  for (const CloudInstance& i : plan.near) {
    EXPECT_TRUE(seen.insert(key(i, c)).second) << "a near copy twice";
    nx0 = std::min(nx0, c.world_min.x + i.offset_m.x);
    nx1 = std::max(nx1, c.world_max.x + i.offset_m.x);
    nz0 = std::min(nz0, c.world_min.z + i.offset_m.z);
    nz1 = std::max(nz1, c.world_max.z + i.offset_m.z);
  }
  ASSERT_GT(plan.far.size(), 50u);
  EXPECT_EQ(plan.left_out, 0u);
  for (const CloudInstance& i : plan.far) {
    // Whole periods, once each, within reach, and clear of the near region (by more than a voxel).
    EXPECT_NEAR(i.offset_m.x / c.period_m.x, std::round(i.offset_m.x / c.period_m.x), 1e-9);
    EXPECT_NEAR(i.offset_m.z / c.period_m.z, std::round(i.offset_m.z / c.period_m.z), 1e-9);
    EXPECT_EQ(i.offset_m.y, 0.0);
    EXPECT_TRUE(seen.insert(key(i, c)).second) << "a copy twice";
    const glm::dvec3 lo = c.world_min + i.offset_m, hi = c.world_max + i.offset_m;
    const double dx = std::max({lo.x - cam.eye.x, 0.0, cam.eye.x - hi.x});
    const double dz = std::max({lo.z - cam.eye.z, 0.0, cam.eye.z - hi.z});
    EXPECT_LE(std::hypot(dx, dz), reach);
    const bool inside = lo.x + 15.0 < nx1 && hi.x - 15.0 > nx0 && lo.z + 15.0 < nz1 && hi.z - 15.0 > nz0;
    EXPECT_FALSE(inside) << "a far copy reaches into the near region";
  }
  // Every copy whose centre is in view and well within reach is drawn; none behind the eye is.
  const CameraFrame f = camera_frame(cam);
  const double tan_x = std::tan(0.5 * cam.fov_deg * M_PI / 180.0), tan_y = tan_x * cam.height / cam.width;
  for (int a = -20; a <= 20; ++a)
    for (int b = -20; b <= 20; ++b) {
      const glm::dvec3 o(100.0 * a, 0.0, 100.0 * b);
      const glm::dvec3 centre = 0.5 * (c.world_min + c.world_max) + o - cam.eye;
      const double z = glm::dot(centre, f.forward);
      const bool in_view = z > 0.0 && std::abs(glm::dot(centre, f.right)) < 0.9 * tan_x * z &&
                           std::abs(glm::dot(centre, f.up)) < 0.9 * tan_y * z;
      const Key k{0, a, b};
      if (in_view && std::hypot(centre.x, centre.z) < reach - 100.0) {
        EXPECT_TRUE(seen.count(k)) << a << ", " << b;
      }
      const glm::dvec3 far_corner = glm::max(c.world_min + o - cam.eye, c.world_max + o - cam.eye);
      if (glm::dot(c.world_max + o - cam.eye, f.forward) < -200.0 && glm::dot(c.world_min + o - cam.eye, f.forward) < -200.0 &&
          far_corner.z < 0.0) {
        EXPECT_FALSE(seen.count(k)) << "a copy behind the eye: " << a << ", " << b;
      }
    }
}

TEST(CloudTiles, ACloudThatDoesNotRepeatTakesTheCopiesUnderItIntoTheNearPass) {
  // A lone cloud two tiles along -z: the copies it overlaps are near, drawn in its pass.
  const std::vector<CloudVolume> clouds = {tile(10, {-45, 0, -45}, true), tile(6, {-20, 5, -230}, false, "lone")};
  const CloudTilePlan plan = plan_cloud_tiles(clouds, sky_camera(), 1500.0);
  bool lone = false, under = false;
  for (const CloudInstance& i : plan.near) {
    lone = lone || (i.cloud == 1 && i.offset_m == glm::dvec3(0.0));
    under = under || (i.cloud == 0 && std::lround(i.offset_m.z / 100.0) == -2);
  }
  EXPECT_TRUE(lone);
  EXPECT_TRUE(under);
  for (const CloudInstance& i : plan.far) {
    EXPECT_EQ(i.cloud, 0u);
    EXPECT_FALSE(std::lround(i.offset_m.x / 100.0) == 0 && std::lround(i.offset_m.z / 100.0) == -2);
  }
}

TEST(CloudTiles, ReachBeyondTheCopyLimitKeepsTheNearest) {
  const std::vector<CloudVolume> clouds = {tile(4, {-15, 0, -15}, true)};  // 40 m tiles
  const Camera cam = sky_camera();
  const CloudTilePlan plan = plan_cloud_tiles(clouds, cam, 1e6);
  EXPECT_EQ(plan.far.size(), kMaxFarCopies);
  EXPECT_GT(plan.left_out, 0u);
  double last = 0.0;
  for (const CloudInstance& i : plan.far) {
    const glm::dvec3 centre = 0.5 * (clouds[0].world_min + clouds[0].world_max) + i.offset_m;
    last = std::max(last, std::hypot(centre.x - cam.eye.x, centre.z - cam.eye.z));
  }
  EXPECT_LE(last, 41.0 * kMaxRepeatsPerAxis * std::sqrt(2.0));
}

TEST(CloudTiles, BadPeriodsAreRefusedNamingTheCloud) {
  const auto refused = [](glm::dvec3 period, const std::string& says) {
    CloudVolume c = tile(10, {0, 0, 0}, false, "field");
    c.period_m = period;
    try {
      validate_period(c);
      ADD_FAILURE() << "accepted " << period.x << ", " << period.y << ", " << period.z;
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("'field'"), std::string::npos) << m;
      EXPECT_NE(m.find(says), std::string::npos) << m;
    }
  };
  refused({-100, 0, 100}, "negative");
  refused({100, 5, 100}, "y must be 0");
  refused({50, 0, 100}, "overlap");
  refused({100, 0, std::nan("")}, "finite");
  CloudVolume ok = tile(10, {0, 0, 0}, true);
  EXPECT_NO_THROW(validate_period(ok));
  ok.period_m = glm::dvec3(0.0, 0.0, 100.0);  // one axis only
  EXPECT_NO_THROW(validate_period(ok));
}

}  // namespace
}  // namespace nimbus::render
