// Moving and blending clouds (render/core/cloud_volume.hpp): a translation moves the density
// exactly; a keyframe blend is linear between the two boxes; bad motions are refused.
#include <gtest/gtest.h>

#include <random>

#include "nimbus/render/core/cloud_volume.hpp"

namespace nimbus::render {
namespace {

CloudVolume box_cloud(float scale, uint32_t seed) {
  openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.0f);
  g->setTransform(openvdb::math::Transform::createLinearTransform(2.5));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto acc = g->getAccessor();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 4; ++k) acc.setValue(openvdb::Coord(i, j - 2, k + 1), scale * u(rng));
  return make_cloud_volume(*g, CloudOptics{}, "box");
}

TEST(CloudMotion, TranslationMovesTheDensityExactly) {
  const CloudVolume a = box_cloud(1.0f, 1);
  CloudVolume b = a;
  const glm::dvec3 o(123.25, -40.5, 7.125);
  translate(b, o);
  EXPECT_EQ(b.world_min, a.world_min + o);
  EXPECT_EQ(b.world_max, a.world_max + o);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-4.0, 16.0);
  double seen = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 p(u(rng), u(rng) - 6.0, u(rng));
    const double da = sample_density(a, p);
    EXPECT_NEAR(sample_density(b, p + o), da, 1e-12);
    seen += da;
  }
  EXPECT_GT(seen, 10.0);
  // The OpenVDB transform moved too (upload_volume reads it).
  const openvdb::Vec3d w = b.transform->indexToWorld(openvdb::Vec3d(1, 2, 3));
  const openvdb::Vec3d w0 = a.transform->indexToWorld(openvdb::Vec3d(1, 2, 3));
  EXPECT_NEAR(w.x() - w0.x(), o.x, 1e-9);
  EXPECT_NEAR(w.z() - w0.z(), o.z, 1e-9);
}

TEST(CloudMotion, BlendIsLinearBetweenKeyframes) {
  CloudVolume a = box_cloud(1.0f, 1);
  const CloudVolume b = box_cloud(0.5f, 7);
  const CloudVolume a0 = a;
  set_next_keyframe(a, b.box, 0.0);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-2.0, 14.0);
  for (double w : {0.0, 0.25, 0.5, 1.0}) {
    apply_motion(a, CloudMotion{glm::dvec3(0.0), w});
    for (int i = 0; i < 300; ++i) {
      const glm::dvec3 p(u(rng), u(rng) - 6.0, u(rng));
      EXPECT_NEAR(sample_density(a, p), (1.0 - w) * sample_density(a0, p) + w * sample_density(b, p), 1e-12);
    }
  }
}

TEST(CloudMotion, BadMotionsAndKeyframesAreRefused) {
  CloudVolume a = box_cloud(1.0f, 1);
  volume::DenseBox other = a.box;
  other.size[0] += 1;
  EXPECT_THROW(set_next_keyframe(a, other, 0.0), std::invalid_argument);
  EXPECT_THROW(set_next_keyframe(a, a.box, 1.5), std::invalid_argument);
  EXPECT_THROW(apply_motion(a, CloudMotion{glm::dvec3(0.0), 0.5}), std::invalid_argument) << "no next keyframe";
  EXPECT_THROW(apply_motion(a, CloudMotion{glm::dvec3(std::nan(""), 0, 0), 0.0}), std::invalid_argument);
  set_next_keyframe(a, a.box, 0.0);
  EXPECT_THROW(apply_motion(a, CloudMotion{glm::dvec3(0.0), -0.1}), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
