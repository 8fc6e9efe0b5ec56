// `nimbus render` and `nimbus bench shafts` from the command line: files written with their
// metadata, and every kind of bad input refused with a clear message and the right exit code.
#include <gtest/gtest.h>

#include <filesystem>

#include "nimbus/render/image/image_io.hpp"
#include "support/run_nimbus.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_render_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(RenderCli, WritesExrWithMetadataAndPreview) {
  const fs::path d = temp_dir("ok");
  const auto r = run_nimbus("render --scene lamps --method shadowvolume:8 --res 64x36 --eye 0,-12,2 --fov 70 -o " +
                            (d / "a.exr").string() + " --preview " + (d / "a.png").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image img = render::read_exr(d / "a.exr");
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 36);
  EXPECT_EQ(img.metadata.at("method"), "shadowvolume:8");
  EXPECT_NE(img.metadata.at("camera").find("eye 0,-12,2"), std::string::npos) << img.metadata.at("camera");
  EXPECT_NE(img.metadata.at("camera").find("fov_deg 70"), std::string::npos);
  EXPECT_NE(img.metadata.at("medium").find("extinction_per_m"), std::string::npos);
  EXPECT_TRUE(fs::exists(d / "a.png"));
  fs::remove_all(d);
}

TEST(RenderCli, ReferenceMethodRunsOnTheCpu) {
  const fs::path d = temp_dir("ref");
  const auto r = run_nimbus("render --scene open --method reference --res 16x9 -o " + (d / "r.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(render::read_exr(d / "r.exr").metadata.at("method"), "reference");
  fs::remove_all(d);
}

TEST(RenderCli, BadInputIsAUsageError) {
  const fs::path d = temp_dir("bad");
  const std::string out = " -o " + (d / "x.exr").string();
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {"--scene nowhere", "--scene"},
      {"--method raymarch:0", "--method"},
      {"--res 0x0", "--res"},
      {"--res 64", "--res"},
      {"--extinction -1", "extinction"},
      {"--extinction nan", "extinction"},
      {"--albedo 2", "albedo"},
      {"--phase hg:1.5", "--phase"},
      {"--eye 1,2", "--eye"},
      {"--eye 0,-12,2 --look-at 0,-12,2", "look_at"},
      {"--fov 180", "fov"},
      {"--scene colonnade --method analytic:table:64", "isotropic"},
  };
  for (const Case& c : cases) {
    const auto r = run_nimbus("render --res 16x9 " + c.args + out);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(d / "x.exr")) << c.args;
  }
  fs::remove_all(d);
}

// The image is always EXR and the preview always PNG: a name saying otherwise is refused before
// anything is rendered or written (it once got EXR bytes under a .png name).
TEST(RenderCli, OutputNamesMustSayWhatIsWritten) {
  const fs::path d = temp_dir("names");
  const struct {
    std::string args, expect;
  } cases[] = {{"-o " + (d / "x.png").string(), "must end in .exr"},
               {"-o " + (d / "x").string(), "must end in .exr"},
               {"-o " + (d / "x.exr").string() + " --preview " + (d / "p.jpg").string(), "must end in .png"}};
  for (const auto& c : cases) {
    const auto r = run_nimbus("render --scene open --method analytic --res 16x9 " + c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_TRUE(fs::is_empty(d)) << c.args;
  }
  const auto ok = run_nimbus("render --scene open --method analytic --res 16x9 -o " + (d / "UPPER.EXR").string());
  EXPECT_EQ(ok.code, 0) << ok.output;
  fs::remove_all(d);
}

TEST(RenderCli, UnwritableOutputIsARuntimeError) {
  const auto r = run_nimbus("render --scene open --method analytic --res 16x9 -o /proc/nimbus/no/such/dir/x.exr");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("/proc/nimbus/no/such/dir"), std::string::npos) << r.output;
}

// With no EGL vendor to load, the GPU methods fail with a one-line error, not a crash.
TEST(RenderCli, NoGlContextIsAClearError) {
  const fs::path d = temp_dir("nogl");
  const auto r = run_command("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json " + std::string(NIMBUS_BINARY) +
                             " render --scene open --method analytic --res 16x9 -o " + (d / "x.exr").string() + " 2>&1");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("needs OpenGL"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "x.exr"));
  fs::remove_all(d);
}

TEST(BenchShaftsCli, SmallRunPrintsTheTableAndPlot) {
  const fs::path d = temp_dir("bench");
  const auto r = run_nimbus("bench shafts --scene open --res 32x18 --repeat 1 --methods raymarch:4,analytic,shadowvolume:4 --plot " +
                            (d / "p.svg").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* m : {"reference", "raymarch:4", "analytic:stable", "shadowvolume:4"})
    EXPECT_NE(r.output.find(m), std::string::npos) << m << "\n" << r.output;
  EXPECT_TRUE(fs::exists(d / "p.svg"));
  fs::remove_all(d);
}

}  // namespace
}  // namespace nimbus::test
