// Generation's shortcuts for the viewer's keyframes: tests saved at one time and read at the next
// (GenerationReuse), and the y-up grid made directly. Both must give the very grid that the plain
// generation gives, bit for bit, and saved tests must never be read for other inputs.
#include <gtest/gtest.h>

#include <stdexcept>

#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/up_axis.hpp"

namespace nimbus::volume {
namespace {

// A small cumulus field (rough, rooted shapes, displacement, evolution) without wind: the case
// of a sky's clouds, whose drift the renderer applies.
CloudParams small_field() {
  CloudParams p = cloud_from_json(load_preset("cumulus-field")["cloud"], "cumulus-field");
  p.field->size_m = {2500.0, 2000.0};
  p.field->periodic = false;
  p.period_m = {0.0, 0.0};
  p.wind = {0.0, 0.0, 0.0};
  p.evolution = 0.05;  // keyframes 30 s apart differ visibly
  return p;
}

// Same active voxels with the same values (bit for bit), same voxel size.
void expect_same_grid(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b, const char* what) {
  ASSERT_EQ(a.activeVoxelCount(), b.activeVoxelCount()) << what;
  EXPECT_EQ(a.voxelSize(), b.voxelSize()) << what;
  auto acc = b.getConstAccessor();
  for (auto it = a.cbeginValueOn(); it; ++it) {
    float v = 0.0f;
    ASSERT_TRUE(acc.probeValue(it.getCoord(), v)) << what << ": voxel " << it.getCoord() << " missing";
    ASSERT_EQ(v, *it) << what << ": voxel " << it.getCoord();
  }
}

GenerateOptions at(double time_s, GenerationReuse* reuse = nullptr) {
  GenerateOptions o;
  o.voxel_size = 40.0;
  o.time = time_s;
  o.origin_m = {130.0, -70.0, 15.0};
  o.reuse = reuse;
  return o;
}

TEST(GenerationReuse, CarriesTheTestsOverTimeAndGivesTheSameVoxels) {
  const CloudParams p = small_field();
  GenerationReuse saved;
  GenerateStats made, reused;
  const auto first = generate_density(p, at(0.0, &saved), &made);
  EXPECT_EQ(saved.reused_blocks, 0);
  ASSERT_FALSE(saved.key.empty());
  expect_same_grid(*first, *generate_density(p, at(0.0)), "the generation that made the saved");
  for (double t : {30.0, 60.0, -30.0}) {
    const auto later = generate_density(p, at(t, &saved), &reused);
    EXPECT_GT(saved.reused_blocks, 0) << t;
    const auto plain = generate_density(p, at(t));
    expect_same_grid(*later, *plain, "a later time with the saved");
    EXPECT_EQ(reused.voxels_visited, made.voxels_visited);
  }
  // The times differ: the test is not passing on one grid generated three times.
  GenerateStats s0, s1;
  generate_density(p, at(0.0), &s0);
  generate_density(p, at(60.0), &s1);
  EXPECT_NE(s0.active_voxels, s1.active_voxels);
  EXPECT_GT(s0.active_voxels, 1000);
}

TEST(GenerationReuse, IsRemadeForOtherInputsAndNeverReadForThem) {
  const CloudParams p = small_field();
  GenerationReuse saved;
  generate_density(p, at(0.0, &saved));
  // Each of these changes what the block and far tests find; the saved is remade, and the grid
  // is the plain one.
  auto check = [&](const CloudParams& q, GenerateOptions o, const char* what) {
    o.reuse = &saved;
    const auto with = generate_density(q, o);
    EXPECT_EQ(saved.reused_blocks, 0) << what;
    o.reuse = nullptr;
    expect_same_grid(*with, *generate_density(q, o), what);
    generate_density(p, at(0.0, &saved));  // back to the first inputs
  };
  GenerateOptions o = at(30.0);
  o.voxel_size = 35.0;
  check(p, o, "another voxel size");
  o = at(30.0);
  o.origin_m.x += 40.0;
  check(p, o, "another origin");
  o = at(30.0);
  o.y_up = true;
  check(p, o, "y-up");
  CloudParams q = p;
  q.displacement *= 1.5;
  check(q, at(30.0), "another displacement");
  q = p;
  q.field->seed += 1;
  check(q, at(30.0), "other shapes");
  q = p;
  q.shear = {0.2, 0.0};
  check(q, at(30.0), "a shear");
  // With wind, the drift differs at every time: the saved of one time is never read at another.
  q = p;
  q.wind = {8.0, -3.0, 0.0};
  GenerationReuse windy;
  generate_density(q, at(0.0, &windy));
  const auto later = generate_density(q, at(30.0, &windy));
  EXPECT_EQ(windy.reused_blocks, 0);
  expect_same_grid(*later, *generate_density(q, at(30.0)), "wind");
  // The same time again is the same drift: read.
  generate_density(q, at(30.0, &windy));
  EXPECT_GT(windy.reused_blocks, 0);
}

TEST(GenerationReuse, AGenerationStoppedPartWaySavesNothing) {
  const CloudParams p = small_field();
  GenerationReuse saved;
  GenerateOptions o = at(0.0, &saved);
  o.progress = [](double done) {
    if (done > 0.3) throw std::runtime_error("stop");
  };
  EXPECT_THROW(generate_density(p, o), std::runtime_error);
  EXPECT_TRUE(saved.key.empty());
  const auto g = generate_density(p, at(30.0, &saved));
  EXPECT_EQ(saved.reused_blocks, 0);
  expect_same_grid(*g, *generate_density(p, at(30.0)), "after a stopped generation");
}

TEST(GenerateYUp, IsTheZUpGridTurnedVoxelForVoxel) {
  const CloudParams p = small_field();
  GenerateOptions o = at(30.0);
  const auto turned = rotate_z_up_to_y_up(*generate_density(p, o));
  o.y_up = true;
  const auto direct = generate_density(p, o);
  ASSERT_GT(direct->activeVoxelCount(), 1000u);
  expect_same_grid(*turned, *direct, "y-up");
  EXPECT_EQ(direct->getName(), "density");
  EXPECT_EQ(direct->getGridClass(), openvdb::GRID_FOG_VOLUME);
  for (const openvdb::Coord c : {openvdb::Coord(0, 0, 0), openvdb::Coord(17, -40, 23)})
    EXPECT_EQ(direct->indexToWorld(c), turned->indexToWorld(c)) << c;
  // A clip is a box of the grid's own (y-up) indices: the same voxels as the whole grid there.
  const openvdb::CoordBBox box = direct->evalActiveVoxelBoundingBox();
  const openvdb::CoordBBox half(box.min(), openvdb::Coord(box.max().x(), (box.min().y() + box.max().y()) / 2, box.max().z()));
  o.clip = half;
  const auto clipped = generate_density(p, o);
  int64_t inside = 0;
  for (auto it = direct->cbeginValueOn(); it; ++it) inside += half.isInside(it.getCoord());
  EXPECT_EQ(int64_t(clipped->activeVoxelCount()), inside);
  EXPECT_GT(inside, 100);
  auto acc = direct->getConstAccessor();
  for (auto it = clipped->cbeginValueOn(); it; ++it) ASSERT_EQ(*it, acc.getValue(it.getCoord()));
}

}  // namespace
}  // namespace nimbus::volume
