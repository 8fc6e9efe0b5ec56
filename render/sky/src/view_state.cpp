// The animated sky's view state and its JSON (view_state.hpp).
#include "nimbus/render/sky/view_state.hpp"

#include <stdexcept>
#include <string>

#include "json_members.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/sky_ranges.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::render {

using namespace json_read;

void validate(const ViewState& s) {
  volume::validate(s.sky);
  validate(static_cast<const RenderRequest&>(s), "view state");
  const std::string time_range = "must be in " + volume::range_text(volume::kSkyTimeRangeS) + " seconds of sky time";
  if (!volume::kSkyTimeRangeS.holds(s.sky_time_s)) bad("view state time.sky: " + time_range);
  if (!volume::kSkyTimeRangeS.holds(s.evolution_time_s)) bad("view state time.evolution: " + time_range);
  check_setting(Setting::Speed, s.speed, "view state " + std::string(setting(Setting::Speed).view_key));
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
    } else if (k == "time") {
      members(v, key, [&](const std::string& tk, const json& tv, const std::string& tkey) {
        if (tk == "sky") s.sky_time_s = number(tv, tkey);
        else if (tk == "evolution") s.evolution_time_s = number(tv, tkey);
        else if (tk == "speed") s.speed = number(tv, tkey);
        else if (tk == "paused") s.paused = volume::json_bool(tv, tkey);
        else bad(tkey + ": unknown key (known: sky, evolution, speed, paused)");
      });
    } else if (k != "nimbus" && k != "version" && !read_render_request_key(s, k, v, key, version)) {
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
  json doc = {{"nimbus", "view state"},
              {"version", kViewStateVersion},
              {"sky", volume::sky_to_json(s.sky)},
              {"time", {{"sky", s.sky_time_s}, {"evolution", s.evolution_time_s}, {"speed", s.speed}, {"paused", s.paused}}}};
  doc.update(render_request_to_json(s));
  return doc;
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
