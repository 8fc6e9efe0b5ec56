// Import errors: a missing file, a text file named .vdb, truncated and corrupted files, a file
// without a float grid and an unknown grid name each give a std::runtime_error whose message
// names the file (and lists the grids for an unknown name); none crashes. Files nimbus wrote
// are sealed with a CRC-32, so every truncation and every flipped byte is caught before
// OpenVDB parses them.
#include <gtest/gtest.h>

#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::make_ball;
using nimbus::test::read_bytes;
using nimbus::test::TempDir;
using nimbus::test::write_bytes;

// Expects read_volume_vdb to throw E, with a one-line message naming the file and `mentions`.
template <class E = std::runtime_error>
std::string expect_read_error(const std::filesystem::path& path, const std::string& mentions,
                              const std::optional<std::string>& grid = std::nullopt) {
  try {
    read_volume_vdb(path, grid);
    ADD_FAILURE() << path << ": read succeeded";
  } catch (const E& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path.string(), 0), 0u) << msg;
    EXPECT_NE(msg.find(mentions), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    return msg;
  }
  return "";
}

std::filesystem::path write_sealed(const TempDir& dir, const std::string& name = "cloud.vdb") {
  const auto path = dir / name;
  write_volume_vdb(path, {make_ball(12, 0.5), make_ball(12, 0.5, "temperature")}, ExportInfo{});
  return path;
}

// A fog volume written by OpenVDB alone, as another tool would: no nimbus seal.
std::filesystem::path write_foreign(const TempDir& dir) {
  const auto path = dir / "foreign.vdb";
  auto grid = make_ball(12, 0.5);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setSaveFloatAsHalf(true);
  openvdb::io::File file(path.string());
  file.write({grid});
  file.close();
  return path;
}

TEST(VolumeIoErrors, MissingFile) {
  TempDir dir;
  expect_read_error(dir / "nowhere.vdb", "no such file");
}

TEST(VolumeIoErrors, DirectoryAndEmptyFile) {
  TempDir dir;
  std::filesystem::create_directories(dir / "d.vdb");
  expect_read_error(dir / "d.vdb", "directory");
  write_bytes(dir / "empty.vdb", "");
  expect_read_error(dir / "empty.vdb", "not a readable OpenVDB file");
}

TEST(VolumeIoErrors, TextFileNamedVdb) {
  TempDir dir;
  write_bytes(dir / "notes.vdb", "This is not a volume.\nJust text, several lines of it.\n");
  expect_read_error(dir / "notes.vdb", "not a readable OpenVDB file");
}

TEST(VolumeIoErrors, TruncatedSealedFile) {
  TempDir dir;
  const auto path = write_sealed(dir);
  const std::string bytes = read_bytes(path);
  write_bytes(path, bytes.substr(0, bytes.size() / 2));
  expect_read_error(path, "truncated");
}

TEST(VolumeIoErrors, FlippedBytesInTheMiddleOfASealedFile) {
  TempDir dir;
  const auto path = write_sealed(dir);
  std::string bytes = read_bytes(path);
  for (size_t i = bytes.size() / 2; i < bytes.size() / 2 + 4; ++i) bytes[i] = char(~bytes[i]);
  write_bytes(path, bytes);
  expect_read_error(path, "corrupt");
}

TEST(VolumeIoErrors, EveryDamagedCopyOfASealedFileIsRefused) {
  // One flipped byte at 97 places through the file (header, metadata, topology, values), and
  // truncation at as many lengths: each is reported, none crashes or reads garbage.
  TempDir dir;
  const auto path = write_sealed(dir);
  const std::string good = read_bytes(path);
  const auto damaged = dir / "damaged.vdb";
  for (int step = 0; step < 97; ++step) {
    const size_t at = good.size() * size_t(step) / 97;
    std::string bytes = good;
    bytes[at] = char(bytes[at] ^ 0x5a);
    write_bytes(damaged, bytes);
    EXPECT_THROW(read_volume_vdb(damaged), std::runtime_error) << "flip at " << at;
    write_bytes(damaged, good.substr(0, at));
    EXPECT_THROW(read_volume_vdb(damaged), std::runtime_error) << "cut at " << at;
  }
}

TEST(VolumeIoErrors, TruncatedForeignFileIsRefusedBeforeOpenVdbReadsIt) {
  // No seal here: the grid offsets are checked against the file size (OpenVDB 10.0.1 itself
  // would read the missing chunk sizes as uninitialised memory), and cuts inside the header are
  // OpenVDB's own errors, rethrown naming the file.
  TempDir dir;
  const auto path = write_foreign(dir);
  EXPECT_FALSE(read_volume_vdb(path).checksum_verified);
  const std::string good = read_bytes(path);
  const auto cut = dir / "cut.vdb";
  write_bytes(cut, good.substr(0, good.size() / 2));
  expect_read_error(cut, "grid 'density' ends at byte");
  for (int step = 1; step < 97; ++step) {
    write_bytes(cut, good.substr(0, good.size() * size_t(step) / 97));
    try {
      read_volume_vdb(cut);
      ADD_FAILURE() << "cut at step " << step << " read without error";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(cut.string(), 0), 0u) << e.what();
    }
  }
}

TEST(VolumeIoErrors, FileRewrittenByAnotherToolWithOurMetadataIsNotCalledCorrupt) {
  // As pyopenvdb's readAll + write would: same grids and file metadata (seal included), new
  // header UUID. The stale seal no longer describes the file; it is ignored, not an error.
  TempDir dir;
  const auto ours = write_sealed(dir);
  openvdb::io::File in(ours.string());
  in.open(false);
  const auto grids = in.getGrids();
  const auto meta = in.getMetadata();
  in.close();
  auto rewritten = dir / "rewritten.vdb";
  openvdb::io::File out(rewritten.string());
  out.write(*grids, *meta);
  out.close();
  const VolumeFile f = read_volume_vdb(rewritten);
  EXPECT_FALSE(f.checksum_verified);
  EXPECT_EQ(f.grid->activeVoxelCount(), make_ball(12, 0.5)->activeVoxelCount());
}

TEST(VolumeIoErrors, FileWithOnlyAnIntGrid) {
  TempDir dir;
  const auto path = dir / "labels.vdb";
  auto labels = openvdb::Int32Grid::create(0);
  labels->tree().setValueOn(openvdb::Coord(1, 2, 3), 7);
  labels->setName("labels");
  openvdb::io::File file(path.string());
  file.write({labels});
  file.close();
  expect_read_error(path, "no float grid");
  expect_read_error(path, "labels (int32)", std::string("labels"));  // exists, but not float
}

TEST(VolumeIoErrors, UnknownGridNameListsTheGrids) {
  TempDir dir;
  const auto path = write_sealed(dir);
  const std::string msg = expect_read_error<GridNotFound>(path, "smoke", std::string("smoke"));
  EXPECT_NE(msg.find("density (float)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("temperature (float)"), std::string::npos) << msg;
}

TEST(VolumeIoErrors, FirstFloatGridWhenThereIsNoDensity) {
  TempDir dir;
  const auto path = dir / "houdini.vdb";
  auto labels = openvdb::Int32Grid::create(0);
  labels->setName("labels");
  auto smoke = make_ball(5, 0.1, "smoke");
  auto heat = make_ball(5, 0.1, "heat");
  openvdb::io::File file(path.string());
  file.write({labels, smoke, heat});
  file.close();
  // OpenVDB lists a file's grids by name (as vdb_print and vdb_render's "first floating-point
  // volume" do), so "heat" comes before "smoke" although it was written after it.
  EXPECT_EQ(read_volume_vdb(path).grid->getName(), "heat");
}

TEST(VolumeIoErrors, NonFiniteValuesInAForeignFileAreRefused) {
  TempDir dir;
  const auto path = dir / "nan.vdb";
  auto grid = make_ball(5, 0.1);
  grid->tree().setValueOn(openvdb::Coord(0, 0, 0), std::numeric_limits<float>::quiet_NaN());
  openvdb::io::File file(path.string());
  file.write({grid});
  file.close();
  expect_read_error(path, "non-finite");
}

}  // namespace
