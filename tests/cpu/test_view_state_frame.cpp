// One frame, two descriptions: a view state saved, loaded and rendered (`nimbus render
// --view-state`) gives the same pixels as the `nimbus render` flags that describe the same frame
// (the clouds, the sky scene and its sun, the camera, the optics and the renderer's settings).
// Both reach FrameRenderer through one light model and one sun set-up (sun_setup.hpp); a field
// that either side dropped or read differently shows here as a pixel that differs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "support/run_nimbus.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

std::string exact(const glm::dvec3& v) {  // shortest round-trip text of each component
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", v.x, v.y, v.z);
  return buf;
}

struct Case {
  const char* name;
  render::MultipleScatteringMethod method;
  const char* cli_method;
};

class ViewStateFrame : public ::testing::TestWithParam<Case> {};

TEST_P(ViewStateFrame, SavedLoadedAndRenderedEqualsTheCliFlagsToTheBit) {
  const Case c = GetParam();
  const fs::path d = fs::temp_directory_path() / ("nimbus_view_state_frame_" + std::string(c.name) + "_" +
                                                  std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  const fs::path cloud = d / "c.vdb";
  const auto g = run_nimbus("generate --preset cumulus-humilis --voxel-size 40 --up y -o " + cloud.string());
  ASSERT_EQ(g.code, 0) << g.output;

  render::ViewState s;
  s.sky.clouds = {volume::SkyCloud{}};
  s.sky.clouds[0].file = cloud.string();
  s.sky.sun_elevation_deg = 30.0;
  s.sky.sun_azimuth_deg = 120.0;
  s.scene = "sky";
  s.camera.eye = {0.0, 300.0, 3000.0};
  s.camera.look_at = {0.0, 900.0, 0.0};
  s.camera.fov_deg = 50.0;
  s.optics.extinction_per_m = 0.04;
  s.optics.albedo = glm::dvec3(0.99);
  s.slices.multiple.method = c.method;
  s.slices.multiple.octaves = 2;
  s.slices.multiple.light_volume.resolution = 32;
  s.slices.multiple.light_volume.photons = 65536;
  s.slices.slices = 96;
  s.slices.light_res = 256;
  s.cloud_shadow_res = 256;
  s.shafts = render::parse_shaft_method("raymarch:24");
  render::save_view_state(s, (d / "state.json").string());
  const render::ViewState loaded = render::load_view_state((d / "state.json").string());
  ASSERT_EQ(render::view_state_to_json(loaded), render::view_state_to_json(s));

  const auto a = run_nimbus("render --view-state " + (d / "state.json").string() + " --res 96x54 -o " +
                            (d / "state.exr").string());
  ASSERT_EQ(a.code, 0) << a.output;
  // The same frame as flags: the sky's sun as a direction (Z up), to the last bit.
  const std::string sun = exact(render::render_to_world(render::sun_direction(s.sky.sun_elevation_deg, s.sky.sun_azimuth_deg)));
  const auto b = run_nimbus("render " + cloud.string() + " --scene sky --sun=" + sun +
                            " --eye 0,-3000,300 --look-at 0,0,900 --fov 50 --res 96x54 --cloud-extinction 0.04"
                            " --cloud-albedo 0.99,0.99,0.99 --cloud-phase dual:0.7,-0.25,0.8 " + c.cli_method +
                            " --slices 96 --light-res 256 --cloud-shadow-res 256 --shafts raymarch:24 -o " +
                            (d / "flags.exr").string());
  ASSERT_EQ(b.code, 0) << b.output;

  const render::Image x = render::read_exr(d / "state.exr"), y = render::read_exr(d / "flags.exr");
  ASSERT_EQ(x.rgba.size(), y.rgba.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < x.rgba.size(); ++i) differ += x.rgba[i] != y.rgba[i];
  EXPECT_EQ(differ, 0u) << "of " << x.rgba.size() << " values";
  // Not an empty sky: the cloud is white against the blue sky, so red varies across the frame.
  std::vector<float> red;
  for (std::size_t i = 0; i < x.rgba.size(); i += 4) red.push_back(x.rgba[i]);
  std::sort(red.begin(), red.end());
  EXPECT_GT(red.back(), 1.5f * red[red.size() / 2]);
  fs::remove_all(d);
}

INSTANTIATE_TEST_SUITE_P(Methods, ViewStateFrame,
                         ::testing::Values(Case{"octaves", render::MultipleScatteringMethod::Octaves,
                                                "--ms-method octaves --multiple 2"},
                                           Case{"light_volume", render::MultipleScatteringMethod::LightVolume,
                                                "--ms-method light-volume --ms-grid 32 --ms-photons 65536"}),
                         [](const ::testing::TestParamInfo<Case>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace nimbus::test
