// The render request (render/sky render_request.hpp): each setting of the one table bound to its
// own field (request_settings.hpp), its JSON round-trips every field, a view
// state is exactly the request plus the sky and the clocks (the same keys, read by the same code),
// and a bad value or key is refused naming it.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "nimbus/render/sky/render_request.hpp"
#include "nimbus/render/sky/request_settings.hpp"
#include "nimbus/render/sky/view_state.hpp"

namespace nimbus::render {
namespace {

using json = nlohmann::json;

// A request with every field away from its default.
RenderRequest unusual_request() {
  RenderRequest r;
  r.scene = "colonnade-sun";
  r.camera.eye = {10.0, 20.0, -30.0};
  r.camera.look_at = {-5.0, 1.0, 7.5};
  r.camera.fov_deg = 33.0;
  r.optics.extinction_per_m = 0.07;
  r.optics.albedo = {0.9, 0.95, 0.97};
  r.optics.phase = dual_lobe_phase(0.6, -0.3, 0.7);
  r.slices.multiple.octaves = 2;
  r.slices.multiple.method = MultipleScatteringMethod::Octaves;
  r.slices.multiple.light_volume.resolution = 40;
  r.slices.multiple.light_volume.photons = 99999;
  r.slices.slices = 77;
  r.slices.light_res = 300;
  r.cloud_shadow_res = 1024;
  r.render_scale = 0.75;
  r.exposure_stops = 1.25;
  r.slices.jitter = false;
  r.grain_filter.on = false;
  r.slices.repeat_to_m = 5000.0;
  r.shafts = parse_shaft_method("shadowvolume:20");
  return r;
}

TEST(RenderRequest, JsonRoundTripsEveryField) {
  const RenderRequest r = unusual_request();
  const json j = render_request_to_json(r);
  const RenderRequest t = render_request_from_json(j, "request");
  EXPECT_EQ(render_request_to_json(t), j);
  EXPECT_EQ(t.scene, "colonnade-sun");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(t.camera.eye[k], r.camera.eye[k], 1e-12);  // through the file's Z-up world and back
    EXPECT_NEAR(t.camera.look_at[k], r.camera.look_at[k], 1e-12);
  }
  EXPECT_EQ(t.camera.fov_deg, 33.0);
  EXPECT_EQ(t.optics.extinction_per_m, 0.07);
  EXPECT_EQ(t.optics.albedo, r.optics.albedo);
  EXPECT_EQ(t.optics.phase.g, 0.6);
  EXPECT_EQ(t.optics.phase.g_back, -0.3);
  EXPECT_EQ(t.optics.phase.forward_weight, 0.7);
  EXPECT_EQ(t.slices.multiple.octaves, 2);
  EXPECT_EQ(t.slices.multiple.method, MultipleScatteringMethod::Octaves);
  EXPECT_EQ(t.slices.multiple.light_volume.resolution, 40);
  EXPECT_EQ(t.slices.multiple.light_volume.photons, 99999);
  EXPECT_EQ(t.slices.slices, 77);
  EXPECT_EQ(t.slices.light_res, 300);
  EXPECT_EQ(t.cloud_shadow_res, 1024);
  EXPECT_EQ(t.render_scale, 0.75);
  EXPECT_EQ(t.exposure_stops, 1.25);
  EXPECT_FALSE(t.slices.jitter);
  EXPECT_FALSE(t.grain_filter.on);
  EXPECT_EQ(t.slices.repeat_to_m, 5000.0);
  EXPECT_EQ(to_string(t.shafts), "shadowvolume:20");
  // Left out, every key takes the request's default.
  EXPECT_EQ(render_request_to_json(render_request_from_json(json::object(), "empty")), render_request_to_json(RenderRequest{}));
}

TEST(RenderRequest, AViewStateIsTheRequestPlusTheSkyAndTheClocks) {
  ViewState s = default_view_state();
  static_cast<RenderRequest&>(s) = unusual_request();
  s.sky_time_s = 40.0;
  const json state = view_state_to_json(s);
  const json request = render_request_to_json(s);
  // Every key of the request's JSON is the view state's, with the same value...
  for (const auto& [key, value] : request.items()) EXPECT_EQ(state.at(key), value) << key;
  // ...and the view state adds only the sky, the clocks and its header.
  for (const auto& [key, value] : state.items())
    if (!request.contains(key)) EXPECT_TRUE(key == "sky" || key == "time" || key == "nimbus" || key == "version") << key;
  // A view state's request part read as a request gives the same request.
  json part = json::object();
  for (const auto& [key, value] : request.items()) part[key] = state.at(key);
  EXPECT_EQ(render_request_to_json(render_request_from_json(part, "part")), request);
  // The defaults agree too: a view state's request is RenderRequest's defaults.
  EXPECT_EQ(render_request_to_json(ViewState{}), render_request_to_json(RenderRequest{}));
}

TEST(RenderRequest, BadValuesAndKeysAreNamed) {
  const auto error_of = [](const json& doc) {
    try {
      render_request_from_json(doc, "request");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::pair<json, std::string> cases[] = {
      {{{"sky", json::object()}}, "request.sky: unknown key (known: scene, camera, optics, renderer)"},
      {{{"scene", "mars"}}, "request scene: unknown name 'mars'"},
      {{{"camera", {{"fov", 0.5}}}}, "request.camera.fov: must be in [1, 179]"},
      {{{"optics", {{"phase", "dual:2"}}}}, "request.optics.phase: "},
      {{{"optics", {{"albedo", {1.5, 0.5, 0.5}}}}}, "request optics: "},
      {{{"renderer", {{"slices", 1}}}}, "request.renderer.slices: must be in [2, 4096]"},
      {{{"renderer", {{"shafts", "reference"}}}}, "request renderer.shafts: the scene under GPU clouds needs a GPU method"},
      {{{"renderer", {{"speed", 2}}}}, "request.renderer.speed: unknown key"},
  };
  for (const auto& [doc, expected] : cases) {
    const std::string error = error_of(doc);
    EXPECT_NE(error.find(expected), std::string::npos) << doc.dump() << " gave: " << error;
  }
}

// Each setting of the table the request holds has a field of its own: set at both ends of its
// range, it reads back (the blur through its radians), moves that field alone, and a value beyond
// the range is refused naming it, the field unchanged. The defaults are the table's.
TEST(RenderRequest, EachSettingIsBoundToItsOwnField) {
  EXPECT_FALSE(in_request(Setting::Speed));  // the view state's clock
  EXPECT_THROW(setting_value(RenderRequest{}, Setting::Speed), std::logic_error);
  RenderRequest still;
  set_setting_defaults(still, SettingDefaults::Still);
  const json base = render_request_to_json(RenderRequest{});
  for (const RenderSetting& s : kRenderSettings) {
    if (!in_request(s.id)) continue;
    SCOPED_TRACE(std::string(s.flag));
    EXPECT_EQ(setting_value(RenderRequest{}, s.id), s.view_default);
    EXPECT_EQ(setting_value(still, s.id), s.still_default);
    const double step = s.integer ? 1.0 : 1e-6 * (s.max - s.min);
    for (const double v : {s.min_open ? s.min + step : s.min, s.max_open ? s.max - step : s.max}) {
      RenderRequest r;
      set_setting_value(r, s.id, v, "NAME");
      EXPECT_NEAR(setting_value(r, s.id), v, 1e-12 * std::max(1.0, std::abs(v)));
      for (const RenderSetting& other : kRenderSettings) {  // no other setting moved
        if (other.id == s.id || !in_request(other.id)) continue;
        EXPECT_EQ(setting_value(r, other.id), other.view_default) << other.flag;
      }
    }
    RenderRequest r;
    try {
      set_setting_value(r, s.id, s.max_open ? s.max : s.max + step, "NAME");
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("NAME: must be in " + range_text(s), 0), 0u) << e.what();
    }
    EXPECT_EQ(setting_value(r, s.id), s.view_default);
  }
}

}  // namespace
}  // namespace nimbus::render
