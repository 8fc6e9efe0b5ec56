// `nimbus render`'s request at the level of the command library, in this process (no program
// spawned): the typed flags (typed_option.hpp) fill typed fields as CLI11 reads them, bad text is
// a parse error naming the flag, and a render with every typed flag spelled out at its default
// gives the very pixels of one with none.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cli.hpp"
#include "render_clouds.hpp"
#include "render_to_image.hpp"
#include "support/vdb_fixtures.hpp"
#include "test_gl_support.hpp"

namespace nimbus::cli {
namespace {

// The args after CLI11 has read `flags` through `nimbus render`'s cloud options.
CloudRenderArgs parsed(std::vector<std::string> flags) {
  CloudRenderArgs a;
  CLI::App cmd("render");
  add_cloud_render_options(&cmd, a);
  std::reverse(flags.begin(), flags.end());  // CLI11 takes them last first
  cmd.parse(flags);
  return a;
}

// The parse error's message for `flags` (empty when they parse).
std::string parse_error(const std::vector<std::string>& flags) {
  try {
    parsed(flags);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

// The picture's summed alpha: pixels' worth of cloud.
double coverage(const render::Image& image) {
  double sum = 0.0;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) sum += image.rgba[i];
  return sum;
}

TEST(RenderCommand, LeftOutFlagsKeepTheLibraryDefaults) {
  const CloudRenderArgs a = parsed({"--preset", "cumulus-humilis"});
  EXPECT_TRUE(a.lamps.empty());
  EXPECT_EQ(a.lamp_intensity_w_sr, glm::dvec3(100.0));
  EXPECT_FALSE(a.spot_axis.has_value());
  EXPECT_EQ(a.spot_cone_deg, glm::dvec2(20.0, 30.0));
  EXPECT_TRUE(a.settings_given.empty());  // --repeat-to and the rest: auto, or the table's
  EXPECT_EQ(render::to_string(a.request.shafts), render::to_string(render::parse_shaft_method(kCloudShaftsDefault)));
  EXPECT_EQ(a.request.optics.albedo, glm::dvec3(render::kCloudAlbedo));
  EXPECT_EQ(a.request.optics.phase, render::kCloudPhase);
  for (const render::RenderSetting& s : render::kRenderSettings) {
    if (!render::in_request(s.id)) continue;
    EXPECT_EQ(render::setting_value(a.request, s.id), s.still_default) << s.flag;
  }
  EXPECT_FALSE(a.ambient.has_value());  // auto
  EXPECT_FALSE(a.ms_method.has_value());
}

TEST(RenderCommand, TypedFlagsFillTypedFields) {
  const CloudRenderArgs a =
      parsed({"--lamp", "1,2,3", "--lamp", "-4,5,6", "--lamp-intensity", "7,8,9", "--spot", "0,0,-2", "--spot-cone", "10,25",
              "--repeat-to", "500", "--shafts", "analytic", "--cloud-albedo", "0.9", "--cloud-phase", "hg:0.5",
              "--ambient", "0.1,0.2,0.3", "--ms-method", "octaves"});
  // Positions and directions are given Z up and held in the renderer's y-up frame (x, z, -y).
  ASSERT_EQ(a.lamps.size(), 2u);
  EXPECT_EQ(a.lamps[0], glm::dvec3(1.0, 3.0, -2.0));
  EXPECT_EQ(a.lamps[1], glm::dvec3(-4.0, 6.0, -5.0));
  EXPECT_EQ(a.lamp_intensity_w_sr, glm::dvec3(7.0, 8.0, 9.0));
  ASSERT_TRUE(a.spot_axis.has_value());
  EXPECT_EQ(*a.spot_axis, glm::dvec3(0.0, -2.0, 0.0));
  EXPECT_EQ(a.spot_cone_deg, glm::dvec2(10.0, 25.0));
  ASSERT_TRUE(a.settings_given.count(render::Setting::RepeatTo));
  EXPECT_EQ(a.request.slices.repeat_to_m, 500.0);
  EXPECT_EQ(a.request.shafts.kind, render::ShaftMethod::Kind::Analytic);
  EXPECT_EQ(a.request.optics.albedo, glm::dvec3(0.9));
  EXPECT_EQ(a.request.optics.phase.g, 0.5);
  EXPECT_EQ(a.request.optics.phase.forward_weight, 1.0);  // hg:G is one lobe
  ASSERT_TRUE(a.ambient.has_value());
  EXPECT_EQ(*a.ambient, glm::dvec3(0.1, 0.2, 0.3));
  ASSERT_TRUE(a.ms_method.has_value());
  EXPECT_EQ(*a.ms_method, render::MultipleScatteringMethod::Octaves);
  // "auto" is a value of its own.
  EXPECT_FALSE(parsed({"--repeat-to", "auto", "--ambient", "auto"}).settings_given.count(render::Setting::RepeatTo));
  // The table's numbers reach the request's fields, in the fields' units.
  const CloudRenderArgs t = parsed({"--slices", "64", "--blur", "10", "--ms-photons", "4096", "--cloud-shadow-res", "128"});
  EXPECT_EQ(t.request.slices.slices, 64);
  EXPECT_DOUBLE_EQ(t.request.slices.blur_cone_rad, 10.0 * 3.14159265358979323846 / 180.0);
  EXPECT_EQ(t.request.slices.multiple.light_volume.photons, 4096);
  EXPECT_EQ(t.request.cloud_shadow_res, 128);
  EXPECT_EQ(t.settings_given.size(), 4u);
}

TEST(RenderCommand, BadTextIsAParseErrorNamingTheFlag) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--lamp", "1,2"}, "--lamp: '1,2'"},
      {{"--lamp-intensity", "hot"}, "--lamp-intensity: 'hot'"},
      {{"--spot", "0,0,0"}, "--spot: '0,0,0' must be a non-zero direction"},
      {{"--spot-cone", "30,20"}, "--spot-cone: '30,20' must be INNER,OUTER degrees"},
      {{"--spot-cone", "0,20"}, "--spot-cone: '0,20'"},
      {{"--spot-cone", "10,181"}, "--spot-cone: '10,181'"},
      {{"--repeat-to", "-1"}, "--repeat-to: must be in [0, 1e+06] metres, got -1"},
      {{"--repeat-to", "2e6"}, "--repeat-to: must be in [0, 1e+06] metres, got 2e+06"},
      {{"--slices", "1.5"}, "--slices: must be in [2, 4096], got 1.5"},
      {{"--ms-photons", "lots"}, "--ms-photons: 'lots' is not an integer"},
      {{"--blur", "90"}, "--blur: must be in [0, 90) degrees, got 90"},
      {{"--shafts", "raymarch:0"}, "--shafts: "},
      {{"--cloud-albedo", "1,2"}, "--cloud-albedo: '1,2'"},
      {{"--cloud-phase", "dual:2"}, "--cloud-phase: "},
      {{"--cloud-phase", "schlick:0.3"}, "--cloud-phase: cloud phase 'schlick:0.3': clouds take Henyey-Greenstein lobes"},
      {{"--cloud-phase", "dual:0.7,-0.25,1.2"}, "--cloud-phase: phase 'dual:0.7,-0.25,1.2': forward_weight (W) must be in [0, 1]"},
      {{"--ambient", "nan"}, "--ambient: 'nan'"},
      {{"--ms-method", "photons"}, "--ms-method: "},
      {{"--ambient", ""}, "--ambient: the value is empty"},
  };
  for (const auto& [flags, expected] : cases) {
    const std::string error = parse_error(flags);
    EXPECT_NE(error.find(expected), std::string::npos) << flags[0] << " " << flags[1] << " gave: '" << error << "'";
  }
}

TEST(RenderCommand, TypedDefaultsSpelledOutGiveTheVeryPixels) {
  NIMBUS_REQUIRE_GL();
  const std::vector<std::string> base = {"--preset", "cumulus-humilis", "--scene", "none", "--res", "64x36", "--slices", "32",
                                         "--multiple", "0"};
  std::vector<std::string> spelled = base;
  for (const char* flag : {"--repeat-to", "auto", "--cloud-phase", "dual:0.7,-0.25,0.8", "--ambient", "auto",
                           "--cloud-albedo", "0.99", "--ms-method", "octaves"})
    spelled.push_back(flag);
  const render::Image a = render_clouds_image(base);
  const render::Image b = render_clouds_image(spelled);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(a.rgba, b.rgba);
  EXPECT_GT(coverage(a), 10.0) << "the cloud covers some of the frame (else the comparison proves nothing)";
  // And a value that is not the default changes them.
  std::vector<std::string> other = base;
  for (const char* flag : {"--cloud-phase", "hg:0.2"}) other.push_back(flag);
  const render::Image hg = render_clouds_image(other);
  EXPECT_NE(hg.rgba, a.rgba);
  // One phase, two spellings: hg:G is the dual lobe (G, any, 1), to the bit.
  std::vector<std::string> dual = base;
  for (const char* flag : {"--cloud-phase", "dual:0.2,-0.5,1"}) dual.push_back(flag);
  EXPECT_EQ(render_clouds_image(dual).rgba, hg.rgba);
}

// A request file is the request the flags make: its scene, camera, optics and renderer render the
// very pixels of the same values given as flags, and a flag given with it overrides the file's
// value, as that flag alone would. A view state is not a request, and is refused naming the file.
TEST(RenderCommand, ARequestFileIsTheFlagsRequest) {
  NIMBUS_REQUIRE_GL();
  test::TempDir dir;
  const std::string file = (dir / "request.json").string();
  test::write_bytes(file, R"({"scene": "none", "camera": {"eye": [1500, -2500, 900], "look_at": [0, 0, 700], "fov": 40},
      "optics": {"phase": "hg:0.3", "multiple": 0, "ms_method": "octaves", "extinction": 0.05},
      "renderer": {"slices": 32, "repeat_to": 0}})");
  const std::vector<std::string> flags = {"--preset", "cumulus-humilis", "--res", "64x36", "--scene", "none",
                                          "--eye", "1500,-2500,900", "--look-at", "0,0,700", "--fov", "40",
                                          "--cloud-phase", "hg:0.3", "--multiple", "0", "--ms-method", "octaves",
                                          "--cloud-extinction", "0.05", "--slices", "32"};
  const render::Image from_flags = render_clouds_image(flags);
  const render::Image from_file = render_clouds_image({"--preset", "cumulus-humilis", "--res", "64x36", "--request", file});
  ASSERT_EQ(from_file.rgba.size(), from_flags.rgba.size());
  EXPECT_EQ(from_file.rgba, from_flags.rgba);
  EXPECT_GT(coverage(from_flags), 5.0) << "the cloud covers some of the frame (else the comparison proves nothing)";
  // A flag over the file: as the flag alone.
  std::vector<std::string> more = flags;
  *(std::find(more.begin(), more.end(), "--slices") + 1) = "64";
  *(std::find(more.begin(), more.end(), "--cloud-phase") + 1) = "hg:0.6";
  const render::Image over = render_clouds_image({"--preset", "cumulus-humilis", "--res", "64x36", "--request", file,
                                                  "--slices", "64", "--cloud-phase", "hg:0.6"});
  EXPECT_EQ(over.rgba, render_clouds_image(more).rgba);
  EXPECT_NE(over.rgba, from_file.rgba);
  // A view state holds a sky and clocks: not a request.
  test::write_bytes(file, R"({"scene": "none", "sky": {}, "time": {}})");
  try {
    render_clouds_image({"--preset", "cumulus-humilis", "--request", file});
    ADD_FAILURE() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("is a view state"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nimbus::cli
