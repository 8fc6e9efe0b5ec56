// View states (render/core/view_state.hpp): the default is valid, JSON and files round-trip, and
// bad contents name their key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "nimbus/render/sky/view_state.hpp"

namespace nimbus::render {
namespace {

using json = nlohmann::json;

std::string error_of(const json& doc) {
  try {
    view_state_from_json(doc, "state");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ViewState, DefaultIsValidAndRoundTrips) {
  ViewState s = default_view_state();
  EXPECT_NO_THROW(validate(s));
  s.camera.eye = glm::dvec3(1, 2, 3);
  s.sky_time_s = 12.5;
  s.evolution_time_s = 11.0;
  s.paused = true;
  s.optics.phase = dual_lobe_phase(0.6, -0.3, 0.7);
  s.slices.multiple.octaves = 3;
  s.slices.multiple.method = MultipleScatteringMethod::Octaves;
  s.slices.multiple.light_volume.resolution = 64;
  s.slices.multiple.light_volume.photons = 123456;
  s.shafts = parse_shaft_method("analytic");
  s.render_scale = 0.5;
  s.exposure_stops = -1.5;
  s.slices.jitter = false;
  s.grain_filter.on = false;
  s.slices.repeat_to_m = 12500.0;
  const json j = view_state_to_json(s);
  const ViewState t = view_state_from_json(j, "state");
  EXPECT_EQ(view_state_to_json(t), j);
  EXPECT_EQ(t.camera.eye, s.camera.eye);
  EXPECT_EQ(t.paused, true);
  EXPECT_EQ(t.slices.jitter, false);
  EXPECT_EQ(t.grain_filter.on, false);
  EXPECT_EQ(t.slices.repeat_to_m, 12500.0);
  EXPECT_EQ(t.optics.phase.g_back, -0.3);
  EXPECT_EQ(t.slices.multiple.method, MultipleScatteringMethod::Octaves);
  EXPECT_EQ(t.slices.multiple.light_volume.resolution, 64);
  EXPECT_EQ(t.slices.multiple.light_volume.photons, 123456);
  // A state saved before the light volume reached the viewer gets its defaults.
  json old = j;
  for (const char* k : {"ms_method", "ms_grid", "ms_photons"}) old["optics"].erase(k);
  old["renderer"].erase("repeat_to");  // and one saved before the sky reached the horizon, 32 km
  old["renderer"].erase("grain_filter");  // or before stills were filtered of their grain: on
  const ViewState u = view_state_from_json(old, "old state");
  EXPECT_TRUE(u.grain_filter.on);
  EXPECT_EQ(u.slices.repeat_to_m, 32000.0);
  EXPECT_EQ(u.slices.multiple.method, MultipleScatteringMethod::LightVolume);
  EXPECT_EQ(u.slices.multiple.light_volume.photons, ViewState{}.slices.multiple.light_volume.photons);
}

TEST(ViewState, FileRoundTripAndErrors) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("nimbus_test_view_state_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const ViewState s = default_view_state();
  save_view_state(s, (dir / "s.json").string());
  EXPECT_EQ(view_state_to_json(load_view_state((dir / "s.json").string())), view_state_to_json(s));
  EXPECT_THROW(load_view_state((dir / "none.json").string()), std::runtime_error);
  std::ofstream(dir / "bad.json") << "[1,";
  EXPECT_THROW(load_view_state((dir / "bad.json").string()), std::runtime_error);
  std::filesystem::remove_all(dir);
}

// Version 2 files hold the camera in the Z-up world; a file with no version (written before
// it) held it Y-up and still loads, converted, to the same view; saving writes version 2.
TEST(ViewState, OldYUpFilesLoadConvertedAndNewOnesAreZUp) {
  json current = view_state_to_json(default_view_state());
  ASSERT_EQ(current.at("version"), kViewStateVersion);
  current["camera"]["eye"] = {300.0, -1500.0, 250.0};  // x east, y north, z up: 250 m up
  current["camera"]["look_at"] = {-900.0, 5200.0, 2150.0};
  json old = current;
  old.erase("version");
  old["camera"]["eye"] = {300.0, 250.0, 1500.0};  // the same point, y up and -z north
  old["camera"]["look_at"] = {-900.0, 2150.0, -5200.0};
  int v_current = 0, v_old = 0;
  const ViewState a = view_state_from_json(current, "current", &v_current);
  const ViewState b = view_state_from_json(old, "old", &v_old);
  EXPECT_EQ(v_current, 2);
  EXPECT_EQ(v_old, 1);
  EXPECT_EQ(a.camera.eye, b.camera.eye);
  EXPECT_EQ(a.camera.look_at, b.camera.look_at);
  EXPECT_EQ(a.camera.eye.y, 250.0);  // the renderer's frame is y-up: the height is its y
  EXPECT_EQ(view_state_to_json(b), current);  // saving the old file writes the current one
  EXPECT_TRUE(view_state_version_note("old.json", 1).find("version 1") != std::string::npos);
  EXPECT_TRUE(view_state_version_note("new.json", 2).empty());
  json future = current;
  future["version"] = 3;
  EXPECT_NE(error_of(future).find("version"), std::string::npos) << error_of(future);
}

TEST(ViewState, BadContentsNameTheKey) {
  const json good = view_state_to_json(default_view_state());
  json j = good;
  j["camera"]["eye"] = j["camera"]["look_at"];
  EXPECT_NE(error_of(j).find("camera"), std::string::npos) << error_of(j);
  j = good;
  j["renderer"]["slices"] = 1;
  EXPECT_NE(error_of(j).find("renderer.slices"), std::string::npos) << error_of(j);
  for (const json& r : {json(-1.0), json(2e6), json("far"), json(nullptr)}) {
    j = good;
    j["renderer"]["repeat_to"] = r;
    EXPECT_NE(error_of(j).find("renderer.repeat_to"), std::string::npos) << error_of(j);
  }
  for (const json& r : {json("yes"), json(1), json(nullptr)}) {
    j = good;
    j["renderer"]["grain_filter"] = r;
    EXPECT_NE(error_of(j).find("renderer.grain_filter"), std::string::npos) << error_of(j);
  }
  j = good;
  j["renderer"]["shafts"] = "reference";
  EXPECT_NE(error_of(j).find("renderer.shafts"), std::string::npos) << error_of(j);
  j = good;
  j["renderer"]["render_scale"] = 0.0;
  EXPECT_NE(error_of(j).find("render_scale"), std::string::npos);
  j = good;
  j["optics"]["phase"] = "dual:2,0,1";
  EXPECT_NE(error_of(j).find("optics.phase"), std::string::npos) << error_of(j);
  j = good;
  j["optics"]["ms_method"] = "diffusion";
  EXPECT_NE(error_of(j).find("optics.ms_method"), std::string::npos) << error_of(j);
  j = good;
  j["optics"]["ms_grid"] = 2;
  EXPECT_NE(error_of(j).find("optics.ms_grid"), std::string::npos) << error_of(j);
  j = good;
  j["optics"]["ms_photons"] = 1.5e6;
  EXPECT_NE(error_of(j).find("optics.ms_photons"), std::string::npos) << error_of(j);
  j = good;
  j["optics"]["ms_photons"] = std::int64_t{1} << 40;
  EXPECT_NE(error_of(j).find("optics.ms_photons"), std::string::npos) << error_of(j);
  j = good;
  j["time"]["speed"] = -1;
  EXPECT_NE(error_of(j).find("time.speed"), std::string::npos);
  j = good;
  j["time"]["sky"] = "soon";
  EXPECT_NE(error_of(j).find("time.sky"), std::string::npos);
  j = good;
  j["camera"]["roll"] = 3;
  EXPECT_NE(error_of(j).find("camera.roll: unknown key"), std::string::npos);
  j = good;
  j.erase("sky");
  EXPECT_NE(error_of(j).find("sky is missing"), std::string::npos);
  EXPECT_NE(error_of(json::array()).find("must be an object"), std::string::npos);
}

}  // namespace
}  // namespace nimbus::render
