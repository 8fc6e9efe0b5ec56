// Density volumes as 3D textures: the texels are the grid's active box (exactly, in R32F), the
// world-to-texture map puts every voxel centre on its texel centre, and bad boxes are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nimbus/render/gl/volume_texture.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

// A 5x3x4 box at index origin (-2, 7, 1) with distinct values, under a scaled, rotated and
// translated transform (the general affine case, as a Y-up export produces).
openvdb::FloatGrid::Ptr pattern_grid() {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  m.preScale(openvdb::Vec3d(0.25, 0.5, 0.75));
  m.postRotate(openvdb::math::X_AXIS, 0.3);
  m.postTranslate(openvdb::Vec3d(10.0, -2.0, 3.0));
  grid->setTransform(openvdb::math::Transform::createLinearTransform(m));
  auto acc = grid->getAccessor();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) acc.setValue(openvdb::Coord(-2 + i, 7 + j, 1 + k), 0.01f * float(1 + i + 5 * j + 15 * k));
  return grid;
}

TEST(VolumeTexture, TexelsAreTheActiveBoxExactly) {
  NIMBUS_REQUIRE_GL();
  const auto grid = pattern_grid();
  const volume::DenseBox box = volume::dense_active_box(*grid);
  const VolumeTexture v = upload_volume(box, grid->transform(), GL_R32F);
  ASSERT_EQ(v.size[0], 5);
  ASSERT_EQ(v.size[1], 3);
  ASSERT_EQ(v.size[2], 4);
  std::vector<float> back(box.values.size());
  glGetTextureImage(v.texture.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
  EXPECT_EQ(back, box.values);
  EXPECT_FLOAT_EQ(v.max_density, 0.6f);
}

TEST(VolumeTexture, HalfFloatKeepsElevenBits) {
  NIMBUS_REQUIRE_GL();
  const auto grid = pattern_grid();
  const volume::DenseBox box = volume::dense_active_box(*grid);
  const VolumeTexture v = upload_volume(box, grid->transform());  // GL_R16F
  std::vector<float> back(box.values.size());
  glGetTextureImage(v.texture.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
  for (std::size_t n = 0; n < back.size(); ++n) EXPECT_NEAR(back[n], box.values[n], box.values[n] * 0x1p-11) << n;
}

TEST(VolumeTexture, VoxelCentresLandOnTexelCentres) {
  NIMBUS_REQUIRE_GL();
  const auto grid = pattern_grid();
  const volume::DenseBox box = volume::dense_active_box(*grid);
  const VolumeTexture v = upload_volume(box, grid->transform(), GL_R32F);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        const openvdb::Vec3d w = grid->transform().indexToWorld(openvdb::Coord(-2 + i, 7 + j, 1 + k));
        const glm::dvec4 tc = v.world_to_texture * glm::dvec4(w.x(), w.y(), w.z(), 1.0);
        EXPECT_NEAR(tc.x, (i + 0.5) / 5.0, 1e-12);
        EXPECT_NEAR(tc.y, (j + 0.5) / 3.0, 1e-12);
        EXPECT_NEAR(tc.z, (k + 0.5) / 4.0, 1e-12);
        for (int a = 0; a < 3; ++a) {
          EXPECT_GT(w[a], v.world_min[a]);
          EXPECT_LT(w[a], v.world_max[a]);
        }
      }
}

TEST(VolumeTexture, BadBoxesAreRefused) {
  NIMBUS_REQUIRE_GL();
  const auto grid = pattern_grid();
  volume::DenseBox box = volume::dense_active_box(*grid);
  volume::DenseBox empty;
  EXPECT_THROW(upload_volume(empty, grid->transform()), std::invalid_argument);
  volume::DenseBox short_values = box;
  short_values.values.pop_back();
  EXPECT_THROW(upload_volume(short_values, grid->transform()), std::invalid_argument);
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_size);
  volume::DenseBox too_long;
  too_long.size = {int64_t(max_size) + 1, 1, 1};
  too_long.values.assign(static_cast<std::size_t>(max_size) + 1, 0.5f);
  try {
    upload_volume(too_long, grid->transform());
    ADD_FAILURE() << "an axis beyond GL_MAX_3D_TEXTURE_SIZE was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("along x"), std::string::npos) << e.what();
  }
  EXPECT_THROW(upload_volume(box, grid->transform(), GL_RGBA8), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::render
