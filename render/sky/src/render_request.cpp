// One frame's render request, its checks and its JSON (render_request.hpp).
#include "nimbus/render/sky/render_request.hpp"

#include <algorithm>
#include <vector>

#include "json_members.hpp"
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

void read_camera(RenderRequest& r, const json& v, const std::string& key, int version) {
  members(v, key, [&](const std::string& ck, const json& cv, const std::string& ckey) {
    if (ck == "eye") r.camera.eye = camera_point(vec3(cv, ckey), version);
    else if (ck == "look_at") r.camera.look_at = camera_point(vec3(cv, ckey), version);
    else if (ck == "fov") r.camera.fov_deg = number(cv, ckey);
    else bad(ckey + ": unknown key (known: eye, look_at, fov)");
  });
}

void read_optics(RenderRequest& r, const json& v, const std::string& key) {
  members(v, key, [&](const std::string& ok, const json& ov, const std::string& okey) {
    if (ok == "extinction") r.optics.extinction_per_m = number(ov, okey);
    else if (ok == "albedo") r.optics.albedo = vec3(ov, okey);
    else if (ok == "phase") r.optics.phase = parsed(ov, okey, "isotropic, hg:G or dual:GF,GB,W", parse_cloud_phase);
    else if (ok == "multiple") r.slices.multiple.octaves = integer(ov, okey);
    else if (ok == "ms_method")
      r.slices.multiple.method = parsed(ov, okey, "light-volume or octaves", parse_multiple_scattering_method);
    else if (ok == "ms_grid") r.slices.multiple.light_volume.resolution = integer(ov, okey);
    else if (ok == "ms_photons") {
      if (!ov.is_number_integer()) bad(okey + " must be an integer");
      r.slices.multiple.light_volume.photons = ov.get<std::int64_t>();
    } else bad(okey + ": unknown key (known: extinction, albedo, phase, multiple, ms_method, ms_grid, ms_photons)");
  });
}

void read_renderer(RenderRequest& r, const json& v, const std::string& key) {
  members(v, key, [&](const std::string& rk, const json& rv, const std::string& rkey) {
    if (rk == "slices") r.slices.slices = integer(rv, rkey);
    else if (rk == "light_res") r.slices.light_res = integer(rv, rkey);
    else if (rk == "cloud_shadow_res") r.cloud_shadow_res = integer(rv, rkey);
    else if (rk == "render_scale") r.render_scale = number(rv, rkey);
    else if (rk == "exposure") r.exposure_stops = number(rv, rkey);
    else if (rk == "jitter") r.slices.jitter = volume::json_bool(rv, rkey);
    else if (rk == "grain_filter") r.grain_filter.on = volume::json_bool(rv, rkey);
    else if (rk == "repeat_to") r.slices.repeat_to_m = number(rv, rkey);
    else if (rk == "shafts") r.shafts = parsed(rv, rkey, "a shaft method such as raymarch:24", parse_shaft_method);
    else bad(rkey + ": unknown key (known: slices, light_res, cloud_shadow_res, render_scale, exposure, jitter, grain_filter, repeat_to, shafts)");
  });
}

}  // namespace

void validate(const RenderRequest& r, const std::string& what) {
  // A number the JSON holds, against the one table's range, named by its key.
  const auto check = [&](Setting id, double value) { check_setting(id, value, what + " " + std::string(setting(id).view_key)); };
  const auto named = [&](const std::string& part, const auto& validate_part) {
    try {
      validate_part();
    } catch (const std::invalid_argument& e) {
      bad(what + " " + part + ": " + e.what());
    }
  };
  check_scene_name(r.scene, what);
  // Below 1 degree the view holds a speck of sky (the table's range, the CLI's --fov's).
  check(Setting::Fov, r.camera.fov_deg);
  named("camera", [&] { validate(r.camera); });
  check(Setting::CloudExtinction, r.optics.extinction_per_m);
  named("optics", [&] { validate(r.optics); });
  const MultipleScattering& ms = r.slices.multiple;
  check(Setting::Multiple, ms.octaves);
  check(Setting::MsGrid, ms.light_volume.resolution);
  check(Setting::MsPhotons, double(ms.light_volume.photons));
  check(Setting::Slices, r.slices.slices);
  check(Setting::LightRes, r.slices.light_res);
  check(Setting::RepeatTo, r.slices.repeat_to_m);
  named("renderer", [&] {
    validate(r.slices);  // what the JSON does not hold: the defaults, or a program's own
    validate(r.grain_filter);
  });
  check(Setting::CloudShadowRes, r.cloud_shadow_res);
  // The renderer draws no less than 1 % of the window's size (sky_renderer.cpp); below it the
  // scale would be silently raised.
  check(Setting::RenderScale, r.render_scale);
  check(Setting::Exposure, r.exposure_stops);
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
  return {{"scene", r.scene},
          {"camera",
           {{"eye", to_json(render_to_world(r.camera.eye))},
            {"look_at", to_json(render_to_world(r.camera.look_at))},
            {"fov", r.camera.fov_deg}}},
          {"optics",
           {{"extinction", r.optics.extinction_per_m},
            {"albedo", to_json(r.optics.albedo)},
            {"phase", to_string(r.optics.phase)},
            {"multiple", r.slices.multiple.octaves},
            {"ms_method", to_string(r.slices.multiple.method)},
            {"ms_grid", r.slices.multiple.light_volume.resolution},
            {"ms_photons", r.slices.multiple.light_volume.photons}}},
          {"renderer",
           {{"slices", r.slices.slices},
            {"light_res", r.slices.light_res},
            {"cloud_shadow_res", r.cloud_shadow_res},
            {"render_scale", r.render_scale},
            {"exposure", r.exposure_stops},
            {"jitter", r.slices.jitter},
            {"grain_filter", r.grain_filter.on},
            {"repeat_to", r.slices.repeat_to_m},
            {"shafts", to_string(r.shafts)}}}};
}

}  // namespace nimbus::render
