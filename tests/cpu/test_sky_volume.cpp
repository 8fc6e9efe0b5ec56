// `nimbus generate --sky`: a sky file's preset clouds as one density volume. Each cloud's voxels
// in the written file are that preset generated alone, moved by its position and the wind's drift
// (half-float rounding apart); flags that make no sense for a sky, and file clouds, are refused.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/sky.hpp"
#include "nimbus/volume/sky_volume.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/run_nimbus.hpp"

namespace nimbus::volume {
namespace {

using test::run_nimbus;
namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("nimbus_skyvol_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Two presets at two places (multiples of the 40 m voxel, as is the drift after 20 s), and a
// cumulus field whose coverage map, named beside the sky file, is black: it adds no voxel.
const char* kSky = R"({
  "clouds": [
    {"preset": "cumulus-humilis", "position": [0, 0, 0], "seed": 3},
    {"preset": "cumulus-mediocris", "position": [4000, 2000, 0], "seed": 5, "overrides": {"coverage": 0.6}},
    {"preset": "cumulus-field", "position": [-6000, 0, 0], "seed": 1,
     "overrides": {"field": {"size": [3000, 3000], "max_diameter": 1000}, "coverage_map": "black.png"}}
  ],
  "wind": [4.0, 2.0, 0.0],
  "voxel_size": 40.0
})";

void write_black_png(const fs::path& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = 8;
  image.height = 8;
  image.format = PNG_FORMAT_GRAY;
  std::vector<uint8_t> px(64, 0);
  ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, px.data(), 0, nullptr)) << image.message;
}

TEST(SkyVolume, EachCloudIsItsPresetAloneMovedByItsPositionAndTheDrift) {
  const fs::path dir = temp_dir();
  {
    std::ofstream f(dir / "sky.json");
    f << kSky;
  }
  write_black_png(dir / "black.png");
  const fs::path out = dir / "sky.vdb";
  const double T = 20.0, vs = 40.0;
  const auto r = run_nimbus("generate --sky " + (dir / "sky.json").string() + " --time 20 -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const VolumeFile file = read_volume_vdb(out);
  ASSERT_TRUE(file.checksum_verified);
  EXPECT_EQ(file.grid->getName(), "density");
  EXPECT_EQ(file.grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_DOUBLE_EQ(file.grid->voxelSize()[0], vs);
  bool preset_sky = false;
  for (const auto& [k, v] : file.metadata)
    if (k == "preset") preset_sky = std::get<std::string>(v) == "sky";
  EXPECT_TRUE(preset_sky);

  const Sky sky = load_sky_file((dir / "sky.json").string());
  auto acc = file.grid->getConstAccessor();
  int64_t expected_active = 0;
  for (std::size_t i = 0; i < 2; ++i) {
    GenerateOptions o;
    o.voxel_size = vs;
    o.time = T;
    const auto alone = generate_density(sky_cloud_params(sky, i), o);
    const glm::dvec3 at = sky.clouds[i].position_m + sky.wind_m_s * T;
    const openvdb::Coord shift(int(std::lround(at.x / vs)), int(std::lround(at.y / vs)), int(std::lround(at.z / vs)));
    ASSERT_GT(alone->activeVoxelCount(), 500u);
    for (auto it = alone->cbeginValueOn(); it; ++it) {
      const float want = *it, got = acc.getValue(it.getCoord() + shift);
      ASSERT_NEAR(got, want, 1e-3f * want + 1e-7f) << "cloud " << i << " voxel " << it.getCoord();
      ASSERT_TRUE(acc.isValueOn(it.getCoord() + shift));
    }
    expected_active += int64_t(alone->activeVoxelCount());
  }
  // Nothing else: the black-mapped field adds no voxel, and the two clouds do not overlap.
  EXPECT_EQ(int64_t(file.grid->activeVoxelCount()), expected_active);

  // --check-only checks everything and writes nothing.
  const fs::path unwritten = dir / "unwritten.vdb";
  const auto c = run_nimbus("--check-only generate --sky " + (dir / "sky.json").string() + " -o " + unwritten.string());
  EXPECT_EQ(c.code, 0) << c.output;
  EXPECT_FALSE(fs::exists(unwritten));
  fs::remove_all(dir);
}

TEST(SkyVolume, FlagsOfOnePresetAndFileCloudsAreRefusedByName) {
  const fs::path dir = temp_dir();
  {
    std::ofstream f(dir / "sky.json");
    f << R"({"clouds": [{"preset": "cumulus-humilis", "position": [0, 0, 0]}], "voxel_size": 40})";
    std::ofstream g(dir / "files.json");
    g << R"({"clouds": [{"preset": "cumulus-humilis"}, {"file": "elsewhere.vdb"}], "voxel_size": 40})";
  }
  const std::string sky = " --sky " + (dir / "sky.json").string() + " -o " + (dir / "o.vdb").string();
  for (const char* flag : {"--preset cumulus-humilis", "--set coverage=0.5", "--brick 0/2", "--params p.json",
                           "--coverage-map m.png", "--seed 3"}) {
    const auto r = run_nimbus(std::string("generate ") + flag + sky);
    EXPECT_EQ(r.code, 2) << flag << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(flag).substr(0, std::string(flag).find(' '))), std::string::npos) << r.output;
  }
  auto r = run_nimbus("generate --sky " + (dir / "files.json").string() + " -o " + (dir / "o.vdb").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("clouds[1]"), std::string::npos) << r.output;
  r = run_nimbus("generate --sky " + (dir / "missing.json").string() + " -o " + (dir / "o.vdb").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("missing.json"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o.vdb"));
  // Too fine a voxel for memory: refused before any voxel.
  r = run_nimbus("generate --sky " + (dir / "sky.json").string() + " --voxel-size 0.01 -o " + (dir / "o.vdb").string());
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("memory"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace nimbus::volume
