// `nimbus render FILE.vdb | --preset NAME` from the command line: clouds over the sky scene and
// alone, the CPU reference, sequences named name.%04d.exr, a nimbus VDB file read back, and bad
// input refused with a clear message and the right exit code.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "nimbus/render/image/image_io.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "support/run_nimbus.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("nimbus_clouds_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A hand-sized steam plume (about 30 voxels across) keeps every run small.
const std::string kSteam = " --preset steam --voxel-size 0.012 --res 48x32 --slices 24 --light-res 64 ";

bool finite_non_negative(const render::Image& img) {
  for (float v : img.rgba)
    if (!std::isfinite(v) || v < 0.0f) return false;
  return true;
}

TEST(RenderCloudsCli, PresetOverTheSkySceneWritesAFinishedFrame) {
  const fs::path d = temp_dir("sky");
  const auto r = run_nimbus("render" + kSteam + "--scene sky --sun 0.5,-0.3,0.6 --multiple 2 -o " +
                            (d / "a.exr").string() + " --preview " + (d / "a.png").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image img = render::read_exr(d / "a.exr");
  EXPECT_EQ(img.width, 48);
  EXPECT_TRUE(finite_non_negative(img));
  EXPECT_EQ(img.metadata.at("scene"), "sky");
  EXPECT_NE(img.metadata.at("lights").find("sun towards 0.5,-0.3,0.6 (z up)"), std::string::npos) << img.metadata.at("lights");
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) ASSERT_EQ(img.rgba[i], 1.0f);  // sky everywhere behind
  EXPECT_TRUE(fs::exists(d / "a.png"));
  fs::remove_all(d);
}

// A periodic field's file says its period (period_m), and render repeats its tile to the horizon
// under the sky (auto), or as far as --repeat-to says; a bad period in a file is a damaged file.
TEST(RenderCloudsCli, APeriodicFieldFileIsRepeatedToTheHorizon) {
  const fs::path d = temp_dir("periodic");
  const std::string field = (d / "sc.vdb").string();
  auto g = run_nimbus("generate --preset stratocumulus-field --voxel-size 200 -o " + field);
  ASSERT_EQ(g.code, 0) << g.output;
  const auto info = run_nimbus("info " + field);
  EXPECT_NE(info.output.find("period_m: 10000 10000"), std::string::npos) << info.output;
  const std::string view = " --scene sky --res 64x36 --slices 32 --light-res 64 --ms-method octaves --sun-elevation 30 "
                           "--eye 0,-4000,300 --look-at 0,30000,1500 --fov 80 ";
  auto r = run_nimbus("render " + field + view + "-o " + (d / "a.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image tiled = render::read_exr(d / "a.exr");
  ASSERT_TRUE(tiled.metadata.count("periodic_copies"));
  EXPECT_NE(tiled.metadata.at("periodic_copies").find("far"), std::string::npos) << tiled.metadata.at("periodic_copies");
  // Without the scene, alpha is the clouds' cover: the copies add cloud toward the horizon, where
  // one tile has ended.
  const std::string alone = " --scene none --res 64x36 --slices 32 --light-res 64 --ms-method octaves --sun-elevation 30 "
                            "--eye 0,-4000,300 --look-at 0,30000,1500 --fov 80 ";
  r = run_nimbus("render " + field + alone + "--repeat-to 32000 -o " + (d / "b.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image copies = render::read_exr(d / "b.exr");
  r = run_nimbus("render " + field + alone + "-o " + (d / "c.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image one = render::read_exr(d / "c.exr");
  EXPECT_FALSE(one.metadata.count("periodic_copies")) << "auto is one tile without the sky";
  double alpha_copies = 0.0, alpha_one = 0.0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      alpha_copies += copies.pixel(x, y)[3];
      alpha_one += one.pixel(x, y)[3];
    }
  EXPECT_GT(alpha_copies, alpha_one + 64.0) << alpha_copies << " against " << alpha_one;
  for (const char* bad : {"-1", "2e6", "far", "nan"}) {
    const auto e = run_nimbus("render " + field + view + "--repeat-to " + bad + " -o " + (d / "c.exr").string());
    EXPECT_EQ(e.code, 2) << bad;
    EXPECT_NE(e.output.find("--repeat-to"), std::string::npos) << e.output;
  }
  // A period that is not two numbers is a damaged file, named.
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValueOn(openvdb::Coord(0, 0, 0), 0.5f);
  volume::ExportInfo ei;
  ei.extra = {{"period_m", std::string("10000 north")}};
  volume::write_volume_vdb(d / "bad.vdb", {grid}, ei);
  const auto e = run_nimbus("render " + (d / "bad.vdb").string() + view + "-o " + (d / "c.exr").string());
  EXPECT_EQ(e.code, 1) << e.output;
  EXPECT_NE(e.output.find("period_m"), std::string::npos) << e.output;
}

TEST(RenderCloudsCli, GeneratedFileAndPresetGiveTheSameImage) {
  const fs::path d = temp_dir("file");
  // nimbus writes z-up files with up_axis metadata; render turns them to y-up as it does presets.
  auto g = run_nimbus("generate --preset steam --voxel-size 0.012 --float -o " + (d / "steam.vdb").string());
  ASSERT_EQ(g.code, 0) << g.output;
  const std::string common = " --scene none --sun 0.3,0.5,0.8 --cloud-extinction 40 --res 40x40 --slices 24 --light-res 64 --no-jitter ";
  auto a = run_nimbus("render " + (d / "steam.vdb").string() + common + "-o " + (d / "f.exr").string());
  ASSERT_EQ(a.code, 0) << a.output;
  auto b = run_nimbus("render --preset steam --voxel-size 0.012" + common + "-o " + (d / "p.exr").string());
  ASSERT_EQ(b.code, 0) << b.output;
  const render::Image f = render::read_exr(d / "f.exr"), p = render::read_exr(d / "p.exr");
  ASSERT_EQ(f.rgba.size(), p.rgba.size());
  double covered = 0, diff = 0;
  for (std::size_t i = 0; i < f.rgba.size(); ++i) {
    diff = std::max(diff, static_cast<double>(std::abs(f.rgba[i] - p.rgba[i])));
    if (i % 4 == 3) covered += p.rgba[i];
  }
  EXPECT_GT(covered, 10.0);  // the plume is in the picture
  EXPECT_LT(diff, 2e-3);     // half-float EXR rounding only
  fs::remove_all(d);
}

TEST(RenderCloudsCli, ReferenceRendersCloudsAloneOnTheCpu) {
  const fs::path d = temp_dir("ref");
  const auto r = run_nimbus("render --preset steam --voxel-size 0.02 --scene none --method reference --res 16x16 -o " +
                            (d / "r.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image img = render::read_exr(d / "r.exr");
  EXPECT_TRUE(finite_non_negative(img));
  EXPECT_EQ(img.metadata.at("method"), "cloud-reference");
  fs::remove_all(d);
}

// The path tracer from the command line: clouds alone, the same seed the same image, and its
// single-bounce image within its noise of the single-scattering reference's.
TEST(RenderCloudsCli, PathTracerRendersCloudsAloneWithItsNoise) {
  const fs::path d = temp_dir("pt");
  const std::string cloud = "render --preset steam --voxel-size 0.02 --scene none --res 16x16 --ambient 0,0,0 ";
  auto r = run_nimbus(cloud + "--method pathtrace --spp 8 --seed 3 -o " + (d / "a.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = run_nimbus(cloud + "--method pathtrace --spp 8 --seed 3 -o " + (d / "b.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image a = render::read_exr(d / "a.exr"), b = render::read_exr(d / "b.exr");
  EXPECT_TRUE(finite_non_negative(a));
  EXPECT_EQ(a.metadata.at("method"), "cloud-path-tracer");
  EXPECT_NE(a.metadata.at("path_tracer").find("8 samples per pixel"), std::string::npos);
  EXPECT_EQ(a.rgba, b.rgba) << "same seed, same image";
  EXPECT_EQ(run_nimbus(cloud + "--method pathtrace --scene sky -o " + (d / "c.exr").string()).code, 2) << "clouds alone";
  EXPECT_EQ(run_nimbus(cloud + "--method pathtrace --spp 0 -o " + (d / "c.exr").string()).code, 2);
  EXPECT_EQ(run_nimbus(cloud + "--method pathtrace --bounces 0 -o " + (d / "c.exr").string()).code, 2);
  EXPECT_FALSE(fs::exists(d / "c.exr"));
  fs::remove_all(d);
}

// Lamps on clouds: the steam-lamp scene (no sun; its street lamp lights the steam, with the
// scene's denser extinction), clouds alone under a --lamp or a --spot, by the slicer and the
// reference, which agree; a spot joining the scene; the lights are named in the metadata.
TEST(RenderCloudsCli, LampsLightSteamInTheirSceneAndAlone) {
  const fs::path d = temp_dir("lamps");
  const auto r = run_nimbus("render" + kSteam + "--scene steam-lamp -o " + (d / "a.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const render::Image img = render::read_exr(d / "a.exr");
  EXPECT_TRUE(finite_non_negative(img));
  EXPECT_NE(img.metadata.at("light").find("point 0.6,3,3.25 (z up)"), std::string::npos) << img.metadata.at("light");
  EXPECT_EQ(img.metadata.at("light").find("sun"), std::string::npos) << img.metadata.at("light");
  EXPECT_NE(img.metadata.at("cloud_optics").find("extinction_per_m 40"), std::string::npos);
  const std::string alone = kSteam + "--scene none --eye 0.3,-0.4,0.15 --look-at 0,0,0.12 --lamp 0.1,0.1,0.6 ";
  const auto s = run_nimbus("render" + alone + "--cloud-extinction 30 -o " + (d / "s.exr").string());
  ASSERT_EQ(s.code, 0) << s.output;
  const auto c = run_nimbus("render" + alone + "--cloud-extinction 30 --method reference -o " + (d / "c.exr").string());
  ASSERT_EQ(c.code, 0) << c.output;
  const render::Image slices = render::read_exr(d / "s.exr"), reference = render::read_exr(d / "c.exr");
  double sum_s = 0.0, sum_c = 0.0;
  for (std::size_t i = 0; i < slices.rgba.size(); i += 4) {
    sum_s += slices.rgba[i];
    sum_c += reference.rgba[i];
  }
  EXPECT_GT(sum_c, 0.0);
  EXPECT_NEAR(sum_s / sum_c, 1.0, 0.05);  // 24 slices: the image's total radiance within 5 %
  const auto p = run_nimbus("render" + alone + "--cloud-extinction 30 --spot 0,0,-1 --spot-cone 2,4 -o " +
                            (d / "p.exr").string());
  ASSERT_EQ(p.code, 0) << p.output;
  const render::Image spot = render::read_exr(d / "p.exr");
  double sum_p = 0.0;
  for (std::size_t i = 0; i < spot.rgba.size(); i += 4) sum_p += spot.rgba[i];
  EXPECT_LT(sum_p, 0.9 * sum_s);  // a narrow cone lights less of the steam
  EXPECT_NE(spot.metadata.at("light").find("spot axis"), std::string::npos);
  // A spot joins a scene's lamps: the street lamp and the spot both light the frame.
  const auto q = run_nimbus("render" + kSteam + "--scene steam-lamp --lamp 0.1,0.1,0.6 --spot 0,0,-1 --spot-cone 10,20 -o " +
                            (d / "q.exr").string());
  ASSERT_EQ(q.code, 0) << q.output;
  const render::Image both = render::read_exr(d / "q.exr");
  EXPECT_TRUE(finite_non_negative(both));
  EXPECT_NE(both.metadata.at("light").find("point 0.6,3,3.25 (z up)"), std::string::npos) << both.metadata.at("light");
  EXPECT_NE(both.metadata.at("light").find("spot axis"), std::string::npos) << both.metadata.at("light");
  fs::remove_all(d);
}

TEST(RenderCloudsCli, FramesWriteANumberedSequence) {
  const fs::path d = temp_dir("seq");
  const auto r = run_nimbus("render" + kSteam + "--scene none --frames 3-4 --fps 12 -o " + (d / "s.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(d / "s.0003.exr"));
  EXPECT_TRUE(fs::exists(d / "s.0004.exr"));
  EXPECT_FALSE(fs::exists(d / "s.exr"));
  EXPECT_EQ(render::read_exr(d / "s.0004.exr").metadata.at("frame"), "4");
  const auto p = run_nimbus("render" + kSteam + "--scene none --frames 1-1 -o " + (d / "t_%03d.exr").string());
  ASSERT_EQ(p.code, 0) << p.output;
  EXPECT_TRUE(fs::exists(d / "t_001.exr"));
  fs::remove_all(d);
}

TEST(RenderCloudsCli, BadInputIsAUsageError) {
  const fs::path d = temp_dir("bad");
  const std::string out = " -o " + (d / "x.exr").string();
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {kSteam + "--method reference", "--scene none"},
      {kSteam + "--method raymarch:8", "--method"},
      {kSteam + "--spot 0,0,-1", "--spot"},
      {kSteam + "--lamp 0,0,1 --spot 0,0,0", "--spot"},
      {kSteam + "--scene none --lamp 0,0,1 --spot 0,0,-1 --spot-cone 30,20", "--spot-cone"},
      {kSteam + "--scene none --lamp 0,1", "--lamp"},
      {kSteam + "--scene none --lamp 0,0,1 --lamp-intensity -5", "--lamp"},
      {kSteam + "--scene steam-lamp --ms-method light-volume", "--ms-method"},
      {kSteam + "--max-lights 0", "--max-lights"},
      {kSteam + "--scene none --lamp 0,0,1 --method pathtrace", "--lamp"},
      {kSteam + "--scene nowhere", "--scene"},
      {kSteam + "--cloud-phase hg:1.5", "--cloud-phase"},
      {kSteam + "--cloud-albedo 2", "albedo"},
      {kSteam + "--slices 1", "--slices"},
      {kSteam + "--multiple 9", "--multiple"},
      {kSteam + "--ms-method diffusion", "--ms-method"},
      {kSteam + "--ms-method light-volume --multiple 2", "--multiple"},
      {kSteam + "--ms-grid 3", "--ms-grid"},
      {kSteam + "--ms-grid 193", "--ms-grid"},
      {kSteam + "--ms-photons 0", "--ms-photons"},
      {kSteam + "--ms-lobes 3", "--ms-lobes"},
      {kSteam + "--ms-diffusion-depth 1001", "--ms-diffusion-depth"},
      {kSteam + "--multiple 2 --ms-diffusion-depth 2", "--ms-diffusion-depth"},
      {kSteam + "--ms-similarity-depth -1", "--ms-similarity-depth"},
      {kSteam + "--multiple 2 --ms-similarity-depth 2", "--ms-similarity-depth"},
      {kSteam + "--ms-occlusion 0", "--ms-occlusion"},
      {kSteam + "--frames 5-2", "--frames"},
      {kSteam + "--sun 0,0,0", "--sun"},
      {kSteam + "--shafts reference", "--shafts"},
      {" --preset no-such-cloud --res 8x8", "--preset"},
  };
  for (const Case& c : cases) {
    const auto r = run_nimbus("render" + c.args + out);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(d / "x.exr"));
  fs::remove_all(d);
}

double radiance_sum(const render::Image& img) {
  double s = 0.0;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4) s += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
  return s;
}

// The slicer's default is the light volume (its build time on stderr, its grid in the metadata);
// --multiple 0 is single scattering; --multiple N alone keeps meaning N octaves.
TEST(RenderCloudsCli, LightVolumeIsTheDefaultAndMultipleZeroIsSingleScattering) {
  const fs::path d = temp_dir("ms");
  const std::string common = kSteam + "--scene none --cloud-extinction 60 --sun 0.3,0.5,0.8 --no-jitter ";
  auto lv = run_nimbus("render" + common + "--ms-photons 20000 --ms-grid 16 -o " + (d / "lv.exr").string());
  ASSERT_EQ(lv.code, 0) << lv.output;
  EXPECT_NE(lv.output.find("light volume built in"), std::string::npos) << lv.output;
  auto ss = run_nimbus("render" + common + "--multiple 0 -o " + (d / "ss.exr").string());
  ASSERT_EQ(ss.code, 0) << ss.output;
  auto oct = run_nimbus("render" + common + "--multiple 2 -o " + (d / "oct.exr").string());
  ASSERT_EQ(oct.code, 0) << oct.output;
  const render::Image a = render::read_exr(d / "lv.exr"), b = render::read_exr(d / "ss.exr"), c = render::read_exr(d / "oct.exr");
  EXPECT_NE(a.metadata.at("light_volume").find("20000 photons"), std::string::npos) << a.metadata.at("light_volume");
  EXPECT_NE(a.metadata.at("slices").find("multiple scattering light-volume"), std::string::npos) << a.metadata.at("slices");
  EXPECT_EQ(b.metadata.count("light_volume"), 0u);
  EXPECT_NE(b.metadata.at("slices").find("octaves 0"), std::string::npos) << b.metadata.at("slices");
  EXPECT_NE(c.metadata.at("slices").find("octaves 2"), std::string::npos) << c.metadata.at("slices");
  EXPECT_GT(radiance_sum(a), radiance_sum(b));  // scattered light only adds
  EXPECT_NE(a.metadata.at("light_volume").find("all light traced"), std::string::npos) << a.metadata.at("light_volume");
  // The deep light diffused: said in the metadata.
  auto dif = run_nimbus("render" + common + "--ms-photons 20000 --ms-grid 16 --ms-diffusion-depth 2 --ms-similarity-depth 1 -o " +
                         (d / "dif.exr").string());
  ASSERT_EQ(dif.code, 0) << dif.output;
  const render::Image e = render::read_exr(d / "dif.exr");
  EXPECT_NE(e.metadata.at("light_volume").find("diffused deeper than 2 transport mean free paths"), std::string::npos)
      << e.metadata.at("light_volume");
  // The similar medium in the deep cells (opt-in): said too.
  EXPECT_NE(e.metadata.at("light_volume").find("similar medium deeper than 1 transport mean free paths"), std::string::npos)
      << e.metadata.at("light_volume");
  EXPECT_EQ(a.metadata.at("light_volume").find("similar medium"), std::string::npos) << a.metadata.at("light_volume");
  fs::remove_all(d);
}

TEST(RenderCloudsCli, MissingOrCorruptFileIsARuntimeError) {
  const fs::path d = temp_dir("missing");
  auto r = run_nimbus("render " + (d / "none.vdb").string() + " --scene none --res 8x8 -o " + (d / "x.exr").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("none.vdb"), std::string::npos) << r.output;
  { std::ofstream(d / "junk.vdb") << "not a vdb"; }
  r = run_nimbus("render " + (d / "junk.vdb").string() + " --scene none --res 8x8 -o " + (d / "x.exr").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_FALSE(fs::exists(d / "x.exr"));
  fs::remove_all(d);
}

}  // namespace
}  // namespace nimbus::test
