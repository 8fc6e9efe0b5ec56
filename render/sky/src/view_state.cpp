// The animated sky's view state and its JSON (view_state.hpp).
#include "nimbus/render/sky/view_state.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/sky_ranges.hpp"
#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/render/core/world_axes.hpp"

namespace nimbus::render {
namespace {

using json = nlohmann::json;

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument(m); }

double number(const json& v, const std::string& key) { return volume::json_number(v, key); }
int integer(const json& v, const std::string& key) { return volume::json_integer(v, key, -1000000000, 1000000000); }
glm::dvec3 vec3(const json& v, const std::string& key) { return volume::json_vec3(v, key); }

json to_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// A camera point of a file of `version` in the renderer's frame: version 2 is Z-up (the world's),
// version 1 was the renderer's own Y-up frame.
glm::dvec3 camera_point(const glm::dvec3& p, int version) { return version >= 2 ? world_to_render(p) : p; }

// A string value read through its parser (parse_cloud_phase, parse_shaft_method...): the key is
// named when it is not a string (`expected` says what it should be) or the parser refuses it.
template <typename Parse>
auto parsed(const json& v, const std::string& key, const char* expected, Parse parse) {
  if (!v.is_string()) bad(key + " must be " + expected);
  try {
    return parse(v.get<std::string>());
  } catch (const std::invalid_argument& e) {
    bad(key + ": " + e.what());
  }
}

// Calls f(key, value) for every member of the object `v` at `key`, which must be one.
template <typename F>
void members(const json& v, const std::string& key, F f) {
  if (!v.is_object()) bad(key + " must be an object");
  for (const auto& [k, x] : v.items()) f(k, x, key + "." + echo(k));  // a key read from a file: short, one line
}

}  // namespace

void validate(const ViewState& s) {
  // A number the JSON holds, against the one table's range, named by its key.
  const auto check = [](Setting id, double value) {
    check_setting(id, value, "view state " + std::string(setting(id).view_key));
  };
  volume::validate(s.sky);
  if (s.scene != "none") {
    // By name: building the scene (its sky's atmosphere tables for another sun) every frame
    // evicted the viewer's own tables from daylight()'s cache, a rebuild of ~200 ms per frame.
    const std::vector<std::string> names = scene_names();
    if (std::find(names.begin(), names.end(), s.scene) == names.end()) {
      std::string known;
      for (const std::string& n : names) known += n + ", ";
      bad("view state scene: unknown name '" + echo(s.scene) + "' (known: " + known + "none)");
    }
  }
  // Below 1 degree the view holds a speck of sky (the table's range, the CLI's --fov's).
  check(Setting::Fov, s.camera.fov_deg);
  try {
    validate(s.camera);
  } catch (const std::invalid_argument& e) {
    bad(std::string("view state camera: ") + e.what());
  }
  const std::string time_range = "must be in " + volume::range_text(volume::kSkyTimeRangeS) + " seconds of sky time";
  if (!volume::kSkyTimeRangeS.holds(s.sky_time_s)) bad("view state time.sky: " + time_range);
  if (!volume::kSkyTimeRangeS.holds(s.evolution_time_s)) bad("view state time.evolution: " + time_range);
  check(Setting::Speed, s.speed);
  check(Setting::CloudExtinction, s.optics.extinction_per_m);
  try {
    validate(s.optics);
  } catch (const std::invalid_argument& e) {
    bad(std::string("view state optics: ") + e.what());
  }
  const MultipleScattering& ms = s.slices.multiple;
  check(Setting::Multiple, ms.octaves);
  check(Setting::MsGrid, ms.light_volume.resolution);
  check(Setting::MsPhotons, double(ms.light_volume.photons));
  check(Setting::Slices, s.slices.slices);
  check(Setting::LightRes, s.slices.light_res);
  check(Setting::RepeatTo, s.slices.repeat_to_m);
  try {
    validate(s.slices);  // what the JSON does not hold: the defaults, or a program's own
    validate(s.grain_filter);
  } catch (const std::invalid_argument& e) {
    bad(std::string("view state renderer: ") + e.what());
  }
  check(Setting::CloudShadowRes, s.cloud_shadow_res);
  // The renderer draws no less than 1 % of the window's size (sky_renderer.cpp); below it the
  // scale would be silently raised.
  check(Setting::RenderScale, s.render_scale);
  check(Setting::Exposure, s.exposure_stops);
  if (s.shafts.kind == ShaftMethod::Kind::Reference)
    bad("view state renderer.shafts: the scene under GPU clouds needs a GPU method, not reference");
}

ViewState view_state_from_json(const json& doc, const std::string& where, int* version_read) {
  ViewState s;
  bool has_sky = false;
  int version = 1;  // no "version": a file from before it, whose camera was Y-up
  if (doc.is_object() && doc.contains("version")) version = volume::json_integer(doc["version"], where + ".version", 1, kViewStateVersion);
  members(doc, where, [&](const std::string& k, const json& v, const std::string& key) {
    if (k == "sky") {
      s.sky = volume::sky_from_json(v, key);
      has_sky = true;
    } else if (k == "scene") {
      if (!v.is_string()) bad(key + " must be a scene name or none");
      s.scene = v.get<std::string>();
    } else if (k == "camera") {
      members(v, key, [&](const std::string& ck, const json& cv, const std::string& ckey) {
        if (ck == "eye") s.camera.eye = camera_point(vec3(cv, ckey), version);
        else if (ck == "look_at") s.camera.look_at = camera_point(vec3(cv, ckey), version);
        else if (ck == "fov") s.camera.fov_deg = number(cv, ckey);
        else bad(ckey + ": unknown key (known: eye, look_at, fov)");
      });
    } else if (k == "time") {
      members(v, key, [&](const std::string& tk, const json& tv, const std::string& tkey) {
        if (tk == "sky") s.sky_time_s = number(tv, tkey);
        else if (tk == "evolution") s.evolution_time_s = number(tv, tkey);
        else if (tk == "speed") s.speed = number(tv, tkey);
        else if (tk == "paused") s.paused = volume::json_bool(tv, tkey);
        else bad(tkey + ": unknown key (known: sky, evolution, speed, paused)");
      });
    } else if (k == "optics") {
      members(v, key, [&](const std::string& ok, const json& ov, const std::string& okey) {
        if (ok == "extinction") s.optics.extinction_per_m = number(ov, okey);
        else if (ok == "albedo") s.optics.albedo = vec3(ov, okey);
        else if (ok == "phase") s.optics.phase = parsed(ov, okey, "isotropic, hg:G or dual:GF,GB,W", parse_cloud_phase);
        else if (ok == "multiple") s.slices.multiple.octaves = integer(ov, okey);
        else if (ok == "ms_method")
          s.slices.multiple.method = parsed(ov, okey, "light-volume or octaves", parse_multiple_scattering_method);
        else if (ok == "ms_grid") s.slices.multiple.light_volume.resolution = integer(ov, okey);
        else if (ok == "ms_photons") {
          if (!ov.is_number_integer()) bad(okey + " must be an integer");
          s.slices.multiple.light_volume.photons = ov.get<std::int64_t>();
        } else bad(okey + ": unknown key (known: extinction, albedo, phase, multiple, ms_method, ms_grid, ms_photons)");
      });
    } else if (k == "renderer") {
      members(v, key, [&](const std::string& rk, const json& rv, const std::string& rkey) {
        if (rk == "slices") s.slices.slices = integer(rv, rkey);
        else if (rk == "light_res") s.slices.light_res = integer(rv, rkey);
        else if (rk == "cloud_shadow_res") s.cloud_shadow_res = integer(rv, rkey);
        else if (rk == "render_scale") s.render_scale = number(rv, rkey);
        else if (rk == "exposure") s.exposure_stops = number(rv, rkey);
        else if (rk == "jitter") s.slices.jitter = volume::json_bool(rv, rkey);
        else if (rk == "grain_filter") s.grain_filter.on = volume::json_bool(rv, rkey);
        else if (rk == "repeat_to") s.slices.repeat_to_m = number(rv, rkey);
        else if (rk == "shafts") s.shafts = parsed(rv, rkey, "a shaft method such as raymarch:24", parse_shaft_method);
        else bad(rkey + ": unknown key (known: slices, light_res, cloud_shadow_res, render_scale, exposure, jitter, grain_filter, repeat_to, shafts)");
      });
    } else if (k != "nimbus" && k != "version") {
      bad(key + ": unknown key (known: version, sky, scene, camera, time, optics, renderer)");
    }
  });
  if (!has_sky) bad(where + ".sky is missing");
  if (version_read) *version_read = version;
  try {
    validate(s);
  } catch (const std::invalid_argument& e) {
    bad(where + ": " + e.what());
  }
  return s;
}

json view_state_to_json(const ViewState& s) {
  return {{"nimbus", "view state"},
          {"version", kViewStateVersion},
          {"sky", volume::sky_to_json(s.sky)},
          {"scene", s.scene},
          {"camera",
           {{"eye", to_json(render_to_world(s.camera.eye))},
            {"look_at", to_json(render_to_world(s.camera.look_at))},
            {"fov", s.camera.fov_deg}}},
          {"time", {{"sky", s.sky_time_s}, {"evolution", s.evolution_time_s}, {"speed", s.speed}, {"paused", s.paused}}},
          {"optics",
           {{"extinction", s.optics.extinction_per_m},
            {"albedo", to_json(s.optics.albedo)},
            {"phase", to_string(s.optics.phase)},
            {"multiple", s.slices.multiple.octaves},
            {"ms_method", to_string(s.slices.multiple.method)},
            {"ms_grid", s.slices.multiple.light_volume.resolution},
            {"ms_photons", s.slices.multiple.light_volume.photons}}},
          {"renderer",
           {{"slices", s.slices.slices},
            {"light_res", s.slices.light_res},
            {"cloud_shadow_res", s.cloud_shadow_res},
            {"render_scale", s.render_scale},
            {"exposure", s.exposure_stops},
            {"jitter", s.slices.jitter},
            {"grain_filter", s.grain_filter.on},
            {"repeat_to", s.slices.repeat_to_m},
            {"shafts", to_string(s.shafts)}}}};
}

ViewState load_view_state(const std::string& path, int* version_read) {
  return view_state_from_json(volume::read_json_file(path, "view state"), "view state '" + path + "'", version_read);
}

void save_view_state(const ViewState& state, const std::string& path) {
  validate(state);
  volume::write_json_file(path, view_state_to_json(state), "view state");
}

std::string view_state_version_note(const std::string& path, int version) {
  if (version >= kViewStateVersion) return {};
  return "view state '" + path + "' has no \"version\": read as version 1, whose camera is Y-up (x east, y up, -z north), and "
         "converted to the Z-up world; save it again (or add \"version\": 2 with a Z-up camera) to update it";
}

ViewState default_view_state() {
  ViewState s;
  s.sky = volume::default_sky();
  return s;
}

}  // namespace nimbus::render
