// Foreign and hostile VDB files: read in an isolated child (the caller survives whatever the
// file does to OpenVDB), refused when they cannot be a density (level sets, degenerate
// transforms, non-finite values, extents no dense copy can index, a few bytes of header), and
// reported truthfully (negative densities counted). nimbus's own sealed files are read in this
// process, after their CRC-32.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

#include "nimbus/base/memory.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/volume/vdb_info.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/sanitizer.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::make_ball;
using nimbus::test::read_bytes;
using nimbus::test::TempDir;
using nimbus::test::write_bytes;

// As another tool writes it: OpenVDB alone, no seal.
void write_foreign(const std::filesystem::path& path, const openvdb::GridCPtrVec& grids) {
  openvdb::io::File file(path.string());
  file.write(grids);
  file.close();
}

std::string read_error(const std::filesystem::path& path, const VdbReadOptions& options = {}) {
  try {
    read_volume_vdb(path, options);
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path.string(), 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    return msg;
  }
  ADD_FAILURE() << path << ": read succeeded";
  return "";
}

TEST(VdbHostile, ForeignFilesAreReadInAChildAndComeBackBitForBit) {
  TempDir dir;
  auto full = make_ball(9, 0.5);
  full->setGridClass(openvdb::GRID_FOG_VOLUME);
  auto half = make_ball(7, 0.25, "smoke");
  half->setSaveFloatAsHalf(true);
  write_foreign(dir / "foreign.vdb", {full, half});

  const VolumeFile f = read_volume_vdb(dir / "foreign.vdb");
  EXPECT_TRUE(f.read_in_child);
  EXPECT_FALSE(f.checksum_verified);
  ASSERT_EQ(f.grids.size(), 2u);
  EXPECT_EQ(f.grid->activeVoxelCount(), full->activeVoxelCount());
  EXPECT_EQ(f.grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_DOUBLE_EQ(f.grid->voxelSize()[0], 0.5);
  for (auto it = full->cbeginValueOn(); it; ++it) ASSERT_EQ(f.grid->tree().getValue(it.getCoord()), *it);

  // The same grid as OpenVDB reads it in this process, half floats and all.
  VdbReadOptions smoke;
  smoke.grid = "smoke";
  const VolumeFile h = read_volume_vdb(dir / "foreign.vdb", smoke);
  openvdb::io::File direct((dir / "foreign.vdb").string());
  direct.open(false);
  const auto expected = openvdb::gridPtrCast<openvdb::FloatGrid>(direct.readGrid("smoke"));
  ASSERT_EQ(h.grid->activeVoxelCount(), expected->activeVoxelCount());
  for (auto it = expected->cbeginValueOn(); it; ++it) ASSERT_EQ(h.grid->tree().getValue(it.getCoord()), *it);

  // nimbus's own sealed file: checked by its CRC and read here, no child.
  write_volume_vdb(dir / "ours.vdb", {make_ball(9, 0.5)}, ExportInfo{});
  const VolumeFile ours = read_volume_vdb(dir / "ours.vdb");
  EXPECT_TRUE(ours.checksum_verified);
  EXPECT_FALSE(ours.read_in_child);
}

TEST(VdbHostile, TheSummaryOfAForeignFileMatchesTheGrids) {
  TempDir dir;
  auto ball = make_ball(6, 0.5);
  auto labels = openvdb::Int32Grid::create(0);
  labels->setName("labels");
  labels->tree().setValueOn(openvdb::Coord(-3, 4, 5), 7);
  write_foreign(dir / "f.vdb", {ball, labels});
  const FileSummary s = summarize_vdb(dir / "f.vdb");
  ASSERT_EQ(s.grids.size(), 2u);
  for (const GridSummary& g : s.grids) {
    if (g.name == "labels") {
      EXPECT_EQ(g.active_voxels, 1u);
      EXPECT_EQ(g.index_min, (std::array<int32_t, 3>{-3, 4, 5}));
    } else {
      EXPECT_EQ(g.active_voxels, ball->activeVoxelCount());
      float lo = 1e30f, hi = -1e30f;
      for (auto it = ball->cbeginValueOn(); it; ++it) {
        lo = std::min(lo, *it);
        hi = std::max(hi, *it);
      }
      ASSERT_TRUE(g.value_range);
      EXPECT_EQ(g.value_range->first, lo);
      EXPECT_EQ(g.value_range->second, hi);
    }
  }
}

TEST(VdbHostile, ExtentsNoDenseCopyCanIndexAreRefusedByName) {
  // Two voxels at either end of the int32 index range: 2^32 - 3 voxels along x. The dense copy
  // once passed the memory check on a large machine, allocated 16.9 GB and crashed.
  TempDir dir;
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValueOn(openvdb::Coord(std::numeric_limits<int32_t>::min() + 1, 0, 0), 0.5f);
  grid->tree().setValueOn(openvdb::Coord(std::numeric_limits<int32_t>::max() - 1, 0, 0), 0.5f);
  write_foreign(dir / "wide.vdb", {grid});
  const VolumeFile f = read_volume_vdb(dir / "wide.vdb");
  EXPECT_EQ(f.grid->activeVoxelCount(), 2u);
  try {
    dense_active_box(*f.grid);
    ADD_FAILURE() << "a dense copy of 2^32 voxels along x was made";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("density"), std::string::npos) << msg;
    EXPECT_NE(msg.find("along x"), std::string::npos) << msg;
  }
  EXPECT_THROW(nimbus::render::load_cloud_file((dir / "wide.vdb").string(), "", nimbus::render::UpAxis::Y,
                                               nimbus::render::CloudOptics{}),
               std::runtime_error);

  // A small box at the far end of the index range: OpenVDB's copy overflowed int32 and crashed.
  auto far = openvdb::FloatGrid::create(0.0f);
  far->setName("density");
  for (int i = 0; i < 4; ++i) far->tree().setValueOn(openvdb::Coord(std::numeric_limits<int32_t>::max() - 2 - i, 5, 5), 0.5f);
  write_foreign(dir / "far.vdb", {far});
  try {
    dense_active_box(*read_volume_vdb(dir / "far.vdb").grid);
    ADD_FAILURE() << "a dense copy at the end of the index range was made";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("2^30"), std::string::npos) << e.what();
  }
}

TEST(VdbHostile, EveryShortPrefixOfAFileIsAnError) {
  // A 4-7 byte prefix of any VDB file once read as a valid file with no grids.
  TempDir dir;
  write_volume_vdb(dir / "ours.vdb", {make_ball(5, 0.5)}, ExportInfo{});
  write_foreign(dir / "foreign.vdb", {make_ball(5, 0.5)});
  for (const char* name : {"ours.vdb", "foreign.vdb"}) {
    const std::string bytes = read_bytes(dir / name);
    for (size_t n = 0; n <= 96; ++n) {
      write_bytes(dir / "cut.vdb", bytes.substr(0, n));
      read_error(dir / "cut.vdb");
      EXPECT_THROW(summarize_vdb(dir / "cut.vdb"), std::runtime_error) << name << " cut to " << n << " bytes";
    }
  }
}

TEST(VdbHostile, LevelSetsAreRefusedUnlessConverted) {
  TempDir dir;
  // A sphere's signed distance: negative inside, a narrow band of 3 voxels each side.
  auto sdf = openvdb::FloatGrid::create(3.0f);
  sdf->setName("surface");
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  for (int i = -12; i <= 12; ++i)
    for (int j = -12; j <= 12; ++j)
      for (int k = -12; k <= 12; ++k) {
        const float d = std::sqrt(float(i * i + j * j + k * k)) - 8.0f;
        if (std::abs(d) < 3.0f) sdf->tree().setValueOn(openvdb::Coord(i, j, k), d);
        else if (d < 0) sdf->tree().setValueOff(openvdb::Coord(i, j, k), -3.0f);
      }
  write_foreign(dir / "sphere.vdb", {sdf});
  const std::string msg = read_error(dir / "sphere.vdb");
  EXPECT_NE(msg.find("level set"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--level-set-to-fog"), std::string::npos) << msg;

  VdbReadOptions convert;
  convert.level_set_to_fog = true;
  const VolumeFile f = read_volume_vdb(dir / "sphere.vdb", convert);
  EXPECT_TRUE(f.from_level_set);
  EXPECT_EQ(f.grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(f.negative_values, 0u);
  const auto acc = f.grid->getConstAccessor();
  EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(0, 0, 0)), 1.0f);     // deep inside
  EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(11, 0, 0)), 0.0f);    // outside
  for (auto it = f.grid->cbeginValueOn(); it; ++it) {
    ASSERT_GE(*it, 0.0f);
    ASSERT_LE(*it, 1.0f);
  }
}

TEST(VdbHostile, NegativeDensitiesAreCountedAndReadAsZeroWithAWarning) {
  TempDir dir;
  auto grid = make_ball(5, 0.5);
  int negatives = 0;
  float least = 0;
  for (auto it = grid->beginValueOn(); it; ++it)
    if (it.getCoord().x() > 2) {
      it.setValue(-0.25f * float(it.getCoord().x()));
      least = std::min(least, *it);
      ++negatives;
    }
  ASSERT_GT(negatives, 10);
  write_foreign(dir / "neg.vdb", {grid});
  const VolumeFile f = read_volume_vdb(dir / "neg.vdb");
  EXPECT_EQ(f.negative_values, uint64_t(negatives));
  EXPECT_EQ(f.min_value, least);

  std::vector<std::string> warnings;
  nimbus::render::CloudFileOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const auto g = nimbus::render::load_cloud_grid((dir / "neg.vdb").string(), "", nimbus::render::UpAxis::Y, nullptr, o);
  for (auto it = g->cbeginValueAll(); it; ++it) ASSERT_GE(*it, 0.0f);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind((dir / "neg.vdb").string(), 0), 0u) << warnings[0];
  EXPECT_NE(warnings[0].find(std::to_string(negatives) + " negative"), std::string::npos) << warnings[0];
}

TEST(VdbHostile, NonFiniteInactiveValuesAndDegenerateTransformsAreRefused) {
  TempDir dir;
  auto nan_inside = make_ball(5, 0.5);
  nan_inside->tree().setValueOff(openvdb::Coord(1, 1, 1), std::numeric_limits<float>::infinity());
  write_foreign(dir / "inf.vdb", {nan_inside});
  EXPECT_NE(read_error(dir / "inf.vdb").find("non-finite"), std::string::npos);

  // A zero scale, written as another tool might (OpenVDB throws when asked for its inverse).
  auto zero = make_ball(5, 0.5);
  write_foreign(dir / "zero.vdb", {zero});
  {
    std::string bytes = read_bytes(dir / "zero.vdb");
    const double half = 0.5, nothing = 0.0;
    size_t patched = 0;
    for (size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&half), 8)); at != std::string::npos && patched < 1;
         at = bytes.find(std::string(reinterpret_cast<const char*>(&half), 8), at + 8), ++patched)
      std::memcpy(&bytes[at], &nothing, 8);  // the scale's x
    ASSERT_EQ(patched, 1u);
    write_bytes(dir / "zero.vdb", bytes);
  }
  const std::string zero_msg = read_error(dir / "zero.vdb");
  EXPECT_TRUE(zero_msg.find("transform") != std::string::npos || zero_msg.find("corrupt") != std::string::npos) << zero_msg;

  // Two index axes mapped almost onto one world direction: invertible, but a world-to-index
  // lookup would amplify rounding by 1e13.
  auto flat = make_ball(5, 0.5);
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  m.setRow(1, openvdb::Vec4d(1.0, 1e-13, 0.0, 0.0));
  flat->setTransform(openvdb::math::Transform::createLinearTransform(m));
  write_foreign(dir / "flat.vdb", {flat});
  EXPECT_NE(read_error(dir / "flat.vdb").find("degenerate transform"), std::string::npos);
}

TEST(VdbHostile, TheReadersLimitsApply) {
  TempDir dir;
  // 128^3 distinct values: 8 MiB of leaf buffers once read, and as much again handed back.
  auto big = openvdb::FloatGrid::create(0.0f);
  big->setName("density");
  auto acc = big->getAccessor();
  for (int i = 0; i < 128; ++i)
    for (int j = 0; j < 128; ++j)
      for (int k = 0; k < 128; ++k) acc.setValueOn(openvdb::Coord(i, j, k), float(i + 128 * (j + 128 * k)) * 1e-6f);
  write_foreign(dir / "f.vdb", {big});
  EXPECT_EQ(read_volume_vdb(dir / "f.vdb").grid->activeVoxelCount(), uint64_t(128 * 128 * 128));
  VdbReadOptions tight;
  tight.limits.seconds = 1e-6;  // the child's timer fires before OpenVDB has opened the file
  EXPECT_NE(read_error(dir / "f.vdb", tight).find("took too long"), std::string::npos);
  tight.limits.seconds = 60;
  tight.limits.memory_bytes = uint64_t(2) << 20;  // 2 MiB more than the process has mapped
  const std::string over_memory = read_error(dir / "f.vdb", tight);
  EXPECT_NE(over_memory.find("0.002 GiB"), std::string::npos) << over_memory;
}

TEST(VdbHostile, ACorruptMetadataLengthCannotExhaustTheCaller) {
  // A grid's metadata string whose length field claims 3e9 bytes: OpenVDB allocates it before
  // reading (9 GB resident in 15 s, once). In the child it meets the limit instead.
  TempDir dir;
  auto grid = make_ball(5, 0.5);
  grid->insertMeta("note", openvdb::StringMetadata("a cloud from elsewhere"));
  write_foreign(dir / "meta.vdb", {grid});
  std::string bytes = read_bytes(dir / "meta.vdb");
  const std::string value = "a cloud from elsewhere";
  const size_t at = bytes.find(value);
  ASSERT_NE(at, std::string::npos);
  const uint32_t huge = 3000000000u;
  std::memcpy(&bytes[at - 4], &huge, 4);
  write_bytes(dir / "meta.vdb", bytes);
  VdbReadOptions o;
  o.limits.memory_bytes = uint64_t(512) << 20;
  const std::string error = read_error(dir / "meta.vdb", o);
  EXPECT_NE(error.find(nimbus::test::kFailedNewAborts ? "crashed" : "NIMBUS_READ_MEMORY_GB"), std::string::npos) << error;
  EXPECT_THROW(summarize_vdb(dir / "meta.vdb", std::nullopt, o.limits), std::runtime_error);
}

TEST(VdbHostile, FilesThatEndOpenVdbInProcessAreErrors) {
  // Damaged foreign files on which OpenVDB 10.0.1 fails an assertion (SIGABRT) or asks for
  // absurd memory (tests/data/hostile-vdb/README.md). Read in this process they would end it.
  const std::filesystem::path dir = std::filesystem::path(NIMBUS_SOURCE_DIR) / "tests/data/hostile-vdb";
  for (const char* name : {"openvdb-asserts-in-delayed-load-mask.vdb", "openvdb-asserts-in-delayed-load-mask-2.vdb",
                           "openvdb-asks-for-absurd-memory.vdb"}) {
    const std::string msg = read_error(dir / name);
    EXPECT_TRUE(msg.find("crashed") != std::string::npos || msg.find("memory") != std::string::npos ||
                msg.find("corrupt") != std::string::npos)
        << msg;
    EXPECT_THROW(summarize_vdb(dir / name), std::runtime_error) << name;
  }
}

TEST(VdbHostile, TheFilesOwnNamesCannotBreakOrFloodTheErrorLine) {
  // A grid named with a line break and 100,000 characters: an error quoting it stays one line
  // of bounded length.
  TempDir dir;
  auto grid = openvdb::Int32Grid::create(0);
  grid->setName("evil\nname" + std::string(100000, 'x'));
  grid->tree().setValueOn(openvdb::Coord(0, 0, 0), 1);
  write_foreign(dir / "names.vdb", {grid});
  for (const std::optional<std::string>& wanted : {std::optional<std::string>(), std::optional<std::string>("nope")}) {
    try {
      VdbReadOptions o;
      o.grid = wanted;
      read_volume_vdb(dir / "names.vdb", o);
      ADD_FAILURE() << "read succeeded";
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.find('\n'), std::string::npos);
      EXPECT_LT(msg.size(), 5000u);
      EXPECT_EQ(msg.rfind((dir / "names.vdb").string(), 0), 0u) << msg.substr(0, 200);
    }
  }
}

TEST(VdbHostile, AFifoIsNotWaitedOn) {
  TempDir dir;
  const auto fifo = dir / "pipe.vdb";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(read_error(fifo).find("not a regular file"), std::string::npos);
}

TEST(VdbHostile, ReadingWhileOtherThreadsHoldOpenVdbsLocksNeverHangs) {
  // The viewer and the farm read foreign files while other threads work. The reader's process
  // must not inherit a lock another thread of the caller held at that moment: a forked copy did
  // (OpenVDB's grid registry here; ASan's allocator in the sanitized suite), and then waited for
  // it until its timer turned a sound file into an error.
  TempDir dir;
  write_foreign(dir / "f.vdb", {make_ball(6, 0.5)});
  std::atomic<bool> stop{false};
  std::vector<std::thread> busy;
  for (int t = 0; t < 3; ++t)
    busy.emplace_back([&] {
      while (!stop.load(std::memory_order_relaxed)) {  // the registry's lock, taken and released
        openvdb::GridBase::Ptr g = openvdb::GridBase::createGrid(openvdb::FloatGrid::gridType());
        openvdb::Metadata::Ptr m = openvdb::Metadata::createMetadata(openvdb::StringMetadata::staticTypeName());
      }
    });
  VdbReadOptions o;
  o.limits.seconds = 20;
  int failed = 0;
  std::string first_error;
  for (int i = 0; i < 40; ++i) {
    try {
      if (read_volume_vdb(dir / "f.vdb", o).grid->activeVoxelCount() == 0) ++failed;
    } catch (const std::runtime_error& e) {
      if (failed++ == 0) first_error = e.what();
    }
  }
  stop = true;
  for (std::thread& t : busy) t.join();
  EXPECT_EQ(failed, 0) << first_error;
}

}  // namespace
