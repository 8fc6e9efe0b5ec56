// Bricks (volume/brick.hpp): the layout cuts a field into 128-voxel-aligned boxes that cover it
// exactly once; bricks generated apart and joined equal the field generated in one process; a
// missing, repeated, foreign or damaged brick is an error naming it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <set>

#include "nimbus/volume/brick.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace {

using namespace nimbus::volume;
namespace fs = std::filesystem;

fs::path temp_dir() {
  auto d = fs::temp_directory_path() / ("nimbus_bricks_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

CloudParams preset(const char* name, int64_t seed = -1) {
  auto doc = load_preset(name);
  if (seed >= 0) doc["cloud"]["seed"] = uint32_t(seed);
  return cloud_from_json(doc.at("cloud"), name);
}

// Every active voxel of a grid.
std::map<std::tuple<int, int, int>, float> voxels(const openvdb::FloatGrid& g) {
  std::map<std::tuple<int, int, int>, float> m;
  for (auto it = g.cbeginValueOn(); it; ++it) m[{it.getCoord().x(), it.getCoord().y(), it.getCoord().z()}] = *it;
  return m;
}

// Brick `i` of `counts` of the field `p` at `vs` metres, written to `dir`; returns its path.
fs::path write_brick(const CloudParams& p, double vs, double time, const std::string& counts, int i, const fs::path& dir,
                     char up = 'z', const std::string& name = "") {
  GenerateOptions o;
  o.voxel_size = vs;
  o.time = time;
  BrickTag tag;
  tag.layout = make_brick_layout(density_index_box(p, vs, time), counts);
  tag.index = i;
  tag.field_id = field_identity(p, o, up, true);
  o.clip = brick_box(tag.layout, i);
  auto g = generate_density(p, o);
  ExportInfo info;
  info.seed = p.seed;
  info.time = time;
  info.up_axis = up;
  info.extra = brick_metadata(tag);
  const fs::path path = dir / (name.empty() ? "brick." + std::to_string(i) + ".vdb" : name);
  write_volume_vdb(path, {g}, info);
  return path;
}

TEST(Bricks, LayoutCoversTheFieldOnceWithWallsOn128VoxelBoundaries) {
  const openvdb::CoordBBox field(openvdb::Coord(-300, -5, 0), openvdb::Coord(400, 260, 70));
  for (const char* counts : {"1", "2", "4", "6", "7", "3x2x1", "2x3x1", "5x1x1", "7x4x1"}) {
    const BrickLayout layout = make_brick_layout(field, counts);
    SCOPED_TRACE(counts);
    int64_t covered = 0;
    for (int i = 0; i < layout.size(); ++i) {
      const openvdb::CoordBBox b = brick_box(layout, i);
      ASSERT_FALSE(b.empty());
      EXPECT_TRUE(field.isInside(b));
      covered += int64_t(b.volume());
      for (int a = 0; a < 3; ++a) {  // a wall inside the field lies on a multiple of 128
        if (b.min()[a] > field.min()[a]) EXPECT_EQ(((b.min()[a] % 128) + 128) % 128, 0);
        if (b.max()[a] < field.max()[a]) EXPECT_EQ((((b.max()[a] + 1) % 128) + 128) % 128, 0);
      }
      for (int j = 0; j < i; ++j) {  // no two bricks overlap
        openvdb::CoordBBox overlap = b;
        overlap.intersect(brick_box(layout, j));
        EXPECT_TRUE(overlap.empty()) << i << " and " << j;
      }
    }
    EXPECT_EQ(covered, int64_t(field.volume()));
  }
  // Blocks of 128: 7 along x (-384..511 covers -300..400), 4 along y (-128..383), 1 along z. One
  // number is cut so that the longest brick side, in blocks, is the shortest it can be.
  EXPECT_EQ(make_brick_layout(field, "4").text(), "2x2x1");  // sides 4, 2, 1 blocks (4x1x1: 2, 4, 1)
  EXPECT_EQ(make_brick_layout(field, "3").text(), "3x1x1");  // sides 3, 4, 1 (1x3x1: 7, 2, 1)
  EXPECT_EQ(make_brick_layout(field, "8").text(), "4x2x1");  // 8x1x1 needs 8 blocks along x
  EXPECT_THROW(make_brick_layout(field, "1x1x2"), std::invalid_argument);  // one block along z
  EXPECT_THROW(make_brick_layout(field, "29"), std::invalid_argument);     // prime, more than 7 blocks
  EXPECT_THROW(make_brick_layout(field, "0"), std::invalid_argument);
  EXPECT_THROW(make_brick_layout(field, "2x2"), std::invalid_argument);
  EXPECT_THROW(make_brick_layout(field, "-1"), std::invalid_argument);
  EXPECT_THROW(brick_box(make_brick_layout(field, "2"), 2), std::out_of_range);
}

TEST(Bricks, FieldIdentityChangesWithEveryInputOfTheField) {
  const CloudParams p = preset("cumulus-humilis");
  GenerateOptions o;
  o.voxel_size = 10;
  const std::string id = field_identity(p, o, 'z', true);
  EXPECT_EQ(id.size(), 16u);
  EXPECT_EQ(id, field_identity(p, o, 'z', true));
  std::set<std::string> ids{id, field_identity(preset("cumulus-humilis", 7), o, 'z', true),
                            field_identity(p, o, 'y', true), field_identity(p, o, 'z', false)};
  GenerateOptions later = o;
  later.time = 1.0;
  GenerateOptions finer = o;
  finer.voxel_size = 9.0;
  ids.insert(field_identity(p, later, 'z', true));
  ids.insert(field_identity(p, finer, 'z', true));
  EXPECT_EQ(ids.size(), 6u);
}

TEST(Bricks, JoinedBricksEqualTheOneProcessFieldVoxelForVoxel) {
  const auto dir = temp_dir() / "join";
  fs::create_directories(dir);
  const CloudParams p = preset("cumulus-field");
  const double vs = 40.0;
  GenerateOptions o;
  o.voxel_size = vs;
  const auto whole = generate_density(p, o);
  for (char up : {'z', 'y'}) {
    SCOPED_TRACE(up);
    std::vector<fs::path> files;
    for (int i : {3, 0, 2, 1}) files.push_back(write_brick(p, vs, 0.0, "2x2x1", i, dir, up, std::string(1, up) + std::to_string(i) + ".vdb"));
    const JoinedField joined = join_bricks(files);
    EXPECT_EQ(joined.layout.text(), "2x2x1");
    EXPECT_EQ(joined.info.up_axis, up);
    ASSERT_EQ(joined.grids.size(), 1u);
    // The bricks were stored as half floats: compare with the whole grid rounded the same way.
    auto expected = voxels(*whole);
    for (auto& [c, v] : expected) v = float(openvdb::math::half(v));
    EXPECT_GT(expected.size(), 50000u);
    EXPECT_EQ(voxels(*joined.grids[0]), expected);
    EXPECT_EQ(joined.active_voxels, int64_t(expected.size()));
  }
}

TEST(Bricks, MissingRepeatedForeignAndDamagedBricksAreErrorsNamingThem) {
  const auto dir = temp_dir() / "errors";
  fs::create_directories(dir);
  const CloudParams p = preset("cumulus-field");
  const double vs = 40.0;
  std::vector<fs::path> b;
  for (int i = 0; i < 4; ++i) b.push_back(write_brick(p, vs, 0.0, "2x2x1", i, dir));
  auto message = [](const std::vector<fs::path>& files) {
    try {
      join_bricks(files);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  std::string m = message({b[0], b[1], b[3]});
  EXPECT_NE(m.find("missing 1 of the 4 bricks"), std::string::npos) << m;
  EXPECT_NE(m.find(": 2 ["), std::string::npos) << m;
  m = message({b[0], b[1], b[2], b[3], b[2]});
  EXPECT_NE(m.find("brick 2 of 2x2x1 is given twice"), std::string::npos) << m;
  const fs::path seed = write_brick(preset("cumulus-field", 9), vs, 0.0, "2x2x1", 2, dir, 'z', "seed9.vdb");
  m = message({b[0], b[1], seed, b[3]});
  EXPECT_NE(m.find("seed9.vdb: a brick of another field"), std::string::npos) << m;
  EXPECT_NE(m.find("seed 9 vs"), std::string::npos) << m;
  const fs::path later = write_brick(p, vs, 5.0, "2x2x1", 2, dir, 'z', "later.vdb");
  m = message({b[0], b[1], later, b[3]});
  EXPECT_NE(m.find("time 5 vs 0"), std::string::npos) << m;
  // Another cut of the same field (one period, 250 voxels at 40 m: two 128-voxel blocks along x).
  const fs::path other_cut = write_brick(p, vs, 0.0, "2x1x1", 1, dir, 'z', "cut.vdb");
  m = message({b[0], b[1], other_cut, b[3]});
  EXPECT_NE(m.find("cut.vdb: a brick of another field"), std::string::npos) << m;
  EXPECT_NE(m.find("brick_layout '2x1x1' vs '2x2x1'"), std::string::npos) << m;

  // Not a brick: a whole field.
  GenerateOptions o;
  o.voxel_size = vs;
  ExportInfo info;
  write_volume_vdb(dir / "whole.vdb", {generate_density(p, o)}, info);
  m = message({b[0], dir / "whole.vdb"});
  EXPECT_NE(m.find("whole.vdb: not a nimbus brick"), std::string::npos) << m;

  // A brick that says it is brick 0 but holds brick 1's voxels.
  GenerateOptions o1 = o;
  BrickTag tag;
  tag.layout = make_brick_layout(density_index_box(p, vs, 0.0), "2x2x1");
  tag.field_id = field_identity(p, o, 'z', true);
  o1.clip = brick_box(tag.layout, 1);
  tag.index = 0;
  info.seed = p.seed;
  info.extra = brick_metadata(tag);
  write_volume_vdb(dir / "liar.vdb", {generate_density(p, o1)}, info);
  m = message({dir / "liar.vdb", b[1], b[2], b[3]});
  EXPECT_NE(m.find("liar.vdb: grid density has voxels outside its brick box"), std::string::npos) << m;
  EXPECT_EQ(message({}), "no brick files given");
}

}  // namespace
