// The nimbus command line: exit codes and messages for bad input, and files any VDB tool reads.
#include <gtest/gtest.h>

#include "support/run_nimbus.hpp"
#include <openvdb/openvdb.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

using Result = nimbus::test::RunResult;
Result run(const std::string& args) { return nimbus::test::run_nimbus(args); }

std::filesystem::path temp_dir() {
  auto d = std::filesystem::temp_directory_path() / ("nimbus_cli_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

TEST(Cli, HelpExitsZero) {
  EXPECT_EQ(run("--help").code, 0);
  EXPECT_EQ(run("noise --help").code, 0);
  EXPECT_EQ(run("bench noise --help").code, 0);
}

TEST(Cli, UsageErrorsExitTwoAndNameTheInput) {
  const auto out = (temp_dir() / "x.vdb").string();
  struct Case {
    std::string args, mentions;
  } cases[] = {
      {"noise --res 0 -o " + out, "--res"},
      {"noise --res -5 -o " + out, "--res"},
      {"noise --octaves 0 --fractal fbm -o " + out, "--octaves"},
      {"noise --octaves 99 --fractal fbm -o " + out, "--octaves"},
      {"noise --frequency nan -o " + out, "--frequency"},
      {"noise --frequency inf -o " + out, "--frequency"},
      {"noise --frequency -1 -o " + out, "--frequency"},
      {"noise --kind simplex -o " + out, "--kind"},
      {"noise --fractal fancy -o " + out, "--fractal"},
      {"noise --octaves 3 -o " + out, "--octaves"},
      {"noise --kind gradient --projected -o " + out, "--projected"},
      {"noise --lacunarity 0.5 --fractal fbm --octaves 2 -o " + out, "lacunarity"},
      {"noise --simd neon -o " + out, "--simd"},
      {"noise --res abc -o " + out, "--res"},
      {"noise", "--output"},
      {"frobnicate", "frobnicate"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, ResolutionBeyondMemoryIsRefusedBeforeAllocating) {
  const auto out = (temp_dir() / "huge.vdb").string();
  const Result r = run("noise --res 4096 -o " + out);  // 4096^3 floats = 256 GiB
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("GiB"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, UnwritableOutputIsARuntimeErrorAndLeavesNoFile) {
  const auto dir = temp_dir() / "is_a_directory.vdb";
  std::filesystem::create_directories(dir);
  const Result r = run("noise --res 8 -o " + dir.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("is_a_directory.vdb"), std::string::npos) << r.output;
  const Result r2 = run("noise --res 8 -o /proc/nimbus_cannot_write_here.vdb");
  EXPECT_EQ(r2.code, 1) << r2.output;
}

TEST(Cli, NoiseFileIsADenseGridNamedNoiseWithSampleSpacingVoxels) {
  const auto path = temp_dir() / "turb.vdb";
  const Result r = run("noise --kind wavelet --fractal turbulence --octaves 3 --frequency 8 --res 16 -o " +
                       path.string());
  ASSERT_EQ(r.code, 0) << r.output;
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  auto base = file.readGrid("noise");
  file.close();
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(16 * 16 * 16));
  EXPECT_DOUBLE_EQ(grid->voxelSize()[0], 8.0 / 16.0);
  float lo = 2, hi = -2;
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    lo = std::min(lo, *it);
    hi = std::max(hi, *it);
  }
  EXPECT_GE(lo, 0.0f);  // turbulence lies in [0, 1]
  EXPECT_LE(hi, 1.0f);
  EXPECT_GT(hi, lo);
  // No temporary file is left beside the output.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(path.parent_path()))
    files += e.path().filename().string().find(".tmp") != std::string::npos;
  EXPECT_EQ(files, 0);
}

}  // namespace
