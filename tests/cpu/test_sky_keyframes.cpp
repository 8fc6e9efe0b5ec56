// Keyframes of a sky's evolution (render/core/sky_keyframes.hpp): each is the model at its time
// on a fixed box, made the same whatever the order of requests, and the wind is a translation.
#include <gtest/gtest.h>

#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/sky/sky_keyframes.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/up_axis.hpp"

namespace nimbus::render {
namespace {

volume::Sky small_sky() {
  volume::Sky s;
  volume::SkyCloud c;
  c.preset = "cumulus-humilis";
  c.position_m = glm::dvec3(300.0, -500.0, 40.0);
  c.seed = 4;
  s.clouds = {c};
  s.wind_m_s = glm::dvec3(6.0, 2.0, 0.0);
  s.evolution_scale = 20.0;  // visibly different keyframes
  s.voxel_size_m = 50.0;
  s.keyframe_interval_s = 10.0;
  return s;
}

TEST(SkyKeyframes, ClockMapsToKeyframeAndBlend) {
  SkyKeyframes kf(small_sky(), CloudOptics{});
  EXPECT_EQ(kf.keyframe_at(0.0), 0);
  EXPECT_EQ(kf.blend_at(0.0), 0.0);
  EXPECT_EQ(kf.keyframe_at(25.0), 2);
  EXPECT_NEAR(kf.blend_at(25.0), 0.5, 1e-12);
  EXPECT_EQ(kf.keyframe_at(-1.0), -1);
  EXPECT_NEAR(kf.blend_at(-1.0), 0.9, 1e-12);
  EXPECT_EQ(kf.keyframe_at(30.0), 3);
  EXPECT_EQ(kf.blend_at(30.0), 0.0);
}

TEST(SkyKeyframes, KeyframeIsTheModelAtItsTimeOnAFixedBox) {
  const volume::Sky sky = small_sky();
  SkyKeyframes kf(sky, CloudOptics{});
  kf.wait(1);
  kf.wait(2);
  const std::vector<CloudVolume> pair = kf.pair(1);
  ASSERT_EQ(pair.size(), 1u);
  const CloudVolume& c = pair[0];
  ASSERT_EQ(c.next_box.size, c.box.size);
  EXPECT_EQ(c.blend, 0.0);
  // The same model generated directly at t = 10 s, turned y-up and placed: equal density at
  // every voxel centre of the box.
  volume::GenerateOptions opt;
  opt.voxel_size = sky.voxel_size_m;
  opt.time = 10.0;
  const openvdb::FloatGrid::Ptr direct =
      volume::rotate_z_up_to_y_up(*volume::generate_density(volume::sky_cloud_params(sky, 0), opt));
  const glm::dvec3 pos(300.0, 40.0, 500.0);  // (x, y, z) z-up -> (x, z, -y)
  auto acc = direct->getConstAccessor();
  double total = 0.0, differ = 0.0;
  for (int64_t k = 0; k < c.box.size[2]; ++k)
    for (int64_t j = 0; j < c.box.size[1]; ++j)
      for (int64_t i = 0; i < c.box.size[0]; ++i) {
        const openvdb::Coord ijk(c.box.origin[0] + static_cast<int>(i), c.box.origin[1] + static_cast<int>(j),
                                 c.box.origin[2] + static_cast<int>(k));
        const float v = c.box.values[static_cast<std::size_t>(i + c.box.size[0] * (j + c.box.size[1] * k))];
        ASSERT_EQ(v, acc.getValue(ijk));
        total += v;
        // Where the box's voxel sits in the world: the direct grid's place, moved by the position.
        const openvdb::Vec3d w = direct->indexToWorld(ijk);
        ASSERT_NEAR(sample_density(c, glm::dvec3(w.x(), w.y(), w.z()) + pos), v, 1e-6);
        differ += std::abs(v - c.next_box.values[static_cast<std::size_t>(i + c.box.size[0] * (j + c.box.size[1] * k))]);
      }
  EXPECT_GT(total, 100.0);
  EXPECT_GT(differ, 0.01 * total) << "the next keyframe has evolved";
  // Every active voxel of the direct grid lies inside the fixed box: nothing is cut off.
  const openvdb::CoordBBox active = direct->evalActiveVoxelBoundingBox();
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(active.min()[a], c.box.origin[a]);
    EXPECT_LT(active.max()[a], c.box.origin[a] + c.box.size[a]);
  }
}

TEST(SkyKeyframes, SameKeyframeWhateverTheOrderOfRequests) {
  SkyKeyframes a(small_sky(), CloudOptics{}), b(small_sky(), CloudOptics{});
  a.wait(3);
  a.wait(4);
  b.request(0, -1);
  b.wait(4);
  b.wait(3);
  EXPECT_EQ(a.pair(3)[0].box.values, b.pair(3)[0].box.values);
  EXPECT_EQ(a.pair(3)[0].next_box.values, b.pair(3)[0].next_box.values);
  EXPECT_THROW(a.pair(40), std::logic_error);
}

TEST(SkyKeyframes, WindIsATranslationYUp) {
  SkyKeyframes kf(small_sky(), CloudOptics{});
  const std::vector<CloudMotion> m = kf.motion(10.0, glm::dvec3(6.0, 2.0, 1.0), 0.25);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].offset_m, glm::dvec3(60.0, 10.0, -20.0));  // (x, y, z) z-up -> (x, z, -y)
  EXPECT_EQ(m[0].blend, 0.25);
}

}  // namespace
}  // namespace nimbus::render
