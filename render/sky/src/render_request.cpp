// One frame's render request, its checks and its JSON (render_request.hpp).
#include "nimbus/render/sky/render_request.hpp"

#include <algorithm>
#include <vector>

#include "json_members.hpp"
#include "nimbus/render/sky/request_settings.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {
namespace {

using namespace json_read;

// A camera point of a file of `version` in the renderer's frame: version 2 is Z-up (the world's),
// version 1 was the renderer's own Y-up frame.
glm::dvec3 camera_point(const glm::dvec3& p, int version) { return version >= 2 ? world_to_render(p) : p; }

void check_scene_name(const std::string& scene, const std::string& what) {
  if (scene == "none") return;
  // By name: building the scene (its sky's atmosphere tables for another sun) every frame
  // evicted the viewer's own tables from daylight()'s cache, a rebuild of ~200 ms per frame.
  const std::vector<std::string> names = scene_names();
  if (std::find(names.begin(), names.end(), scene) != names.end()) return;
  std::string known;
  for (const std::string& n : names) known += n + ", ";
  bad(what + " scene: unknown name '" + echo(scene) + "' (known: " + known + "none)");
}

// A number of the one table at "<section>.<k>" read into its field (request_settings.hpp), its
// range checked naming `key`; false when no setting has that key.
bool read_setting(RenderRequest& r, const std::string& section, const std::string& k, const json& v,
                  const std::string& key) {
  const Setting id = setting_at_view_key(section, k);
  if (id == Setting::Count) return false;
  double value = 0.0;
  if (setting(id).integer) {
    if (!v.is_number_integer()) bad(key + " must be an integer");
    value = v.is_number_unsigned() ? double(v.get<std::uint64_t>()) : double(v.get<std::int64_t>());
  } else {
    value = number(v, key);
  }
  set_setting_value(r, id, value, key);
  return true;
}

// "eye, look_at, fov": a section's keys, its own then the table's, for an unknown key's error.
std::string known_keys(const std::string& section, const std::string& own) {
  std::string known = own;
  for (const RenderSetting& s : kRenderSettings)
    if (s.view_key.substr(0, s.view_key.find('.')) == section)
      known += ", " + std::string(s.view_key.substr(s.view_key.find('.') + 1));
  return known;
}

void read_camera(RenderRequest& r, const json& v, const std::string& key, int version) {
  members(v, key, [&](const std::string& ck, const json& cv, const std::string& ckey) {
    if (read_setting(r, "camera", ck, cv, ckey)) return;
    if (ck == "eye") r.camera.eye = camera_point(vec3(cv, ckey), version);
    else if (ck == "look_at") r.camera.look_at = camera_point(vec3(cv, ckey), version);
    else bad(ckey + ": unknown key (known: " + known_keys("camera", "eye, look_at") + ")");
  });
}

void read_optics(RenderRequest& r, const json& v, const std::string& key) {
  members(v, key, [&](const std::string& ok, const json& ov, const std::string& okey) {
    if (read_setting(r, "optics", ok, ov, okey)) return;
    if (ok == "albedo") r.optics.albedo = vec3(ov, okey);
    else if (ok == "phase") r.optics.phase = parsed(ov, okey, "isotropic, hg:G or dual:GF,GB,W", parse_cloud_phase);
    else if (ok == "ms_method")
      r.slices.multiple.method = parsed(ov, okey, "light-volume or octaves", parse_multiple_scattering_method);
    else bad(okey + ": unknown key (known: " + known_keys("optics", "albedo, phase, ms_method") + ")");
  });
}

void read_renderer(RenderRequest& r, const json& v, const std::string& key) {
  members(v, key, [&](const std::string& rk, const json& rv, const std::string& rkey) {
    if (read_setting(r, "renderer", rk, rv, rkey)) return;
    if (rk == "jitter") r.slices.jitter = volume::json_bool(rv, rkey);
    else if (rk == "grain_filter") r.grain_filter.on = volume::json_bool(rv, rkey);
    else if (rk == "shafts") r.shafts = parsed(rv, rkey, "a shaft method such as raymarch:24", parse_shaft_method);
    else bad(rkey + ": unknown key (known: " + known_keys("renderer", "jitter, grain_filter, shafts") + ")");
  });
}

}  // namespace

RenderRequest::RenderRequest() { set_setting_defaults(*this, SettingDefaults::View); }

void validate(const RenderRequest& r, const std::string& what) {
  // A number against the one table's range, named by its key (by its flag where a file does not
  // hold it).
  const auto check = [&](Setting id, double value) {
    const RenderSetting& s = setting(id);
    check_setting(id, value, what + " " + (s.view_key.empty() ? flag_name(s) : std::string(s.view_key)));
  };
  const auto named = [&](const std::string& part, const auto& validate_part) {
    try {
      validate_part();
    } catch (const std::invalid_argument& e) {
      bad(what + " " + part + ": " + e.what());
    }
  };
  check_scene_name(r.scene, what);
  // Every number of the table the request holds, against its range (a program's own request is
  // not checked as its JSON is read).
  for (const RenderSetting& s : kRenderSettings)
    if (in_request(s.id)) check(s.id, setting_value(r, s.id));
  named("camera", [&] { validate(r.camera); });
  named("optics", [&] { validate(r.optics); });
  named("renderer", [&] {
    validate(r.slices);  // what the JSON does not hold: the defaults, or a program's own
    validate(r.grain_filter);
  });
  if (r.shafts.kind == ShaftMethod::Kind::Reference)
    bad(what + " renderer.shafts: the scene under GPU clouds needs a GPU method, not reference");
}

bool read_render_request_key(RenderRequest& r, const std::string& k, const json& v, const std::string& key,
                             int camera_version) {
  if (k == "scene") {
    if (!v.is_string()) bad(key + " must be a scene name or none");
    r.scene = v.get<std::string>();
  } else if (k == "camera") {
    read_camera(r, v, key, camera_version);
  } else if (k == "optics") {
    read_optics(r, v, key);
  } else if (k == "renderer") {
    read_renderer(r, v, key);
  } else {
    return false;
  }
  return true;
}

RenderRequest render_request_from_json(const json& doc, const std::string& where) {
  RenderRequest r;
  members(doc, where, [&](const std::string& k, const json& v, const std::string& key) {
    if (!read_render_request_key(r, k, v, key, 2)) bad(key + ": unknown key (known: scene, camera, optics, renderer)");
  });
  try {
    validate(r);
  } catch (const std::invalid_argument& e) {
    bad(where + ": " + e.what());
  }
  return r;
}

json render_request_to_json(const RenderRequest& r) {
  json doc = {{"scene", r.scene},
              {"camera", {{"eye", to_json(render_to_world(r.camera.eye))}, {"look_at", to_json(render_to_world(r.camera.look_at))}}},
              {"optics",
               {{"albedo", to_json(r.optics.albedo)},
                {"phase", to_string(r.optics.phase)},
                {"ms_method", to_string(r.slices.multiple.method)}}},
              {"renderer",
               {{"jitter", r.slices.jitter}, {"grain_filter", r.grain_filter.on}, {"shafts", to_string(r.shafts)}}}};
  // The table's numbers at their view keys (an integer setting as a JSON integer).
  for (const RenderSetting& s : kRenderSettings) {
    if (s.view_key.empty() || !in_request(s.id)) continue;
    const std::size_t dot = s.view_key.find('.');
    const double v = setting_value(r, s.id);
    doc[std::string(s.view_key.substr(0, dot))][std::string(s.view_key.substr(dot + 1))] =
        s.integer ? json(std::int64_t(v)) : json(v);
  }
  return doc;
}

}  // namespace nimbus::render
