// Sky files (sky.hpp): parsing with errors that name the key, and each cloud's model parameters.
#include "nimbus/volume/sky.hpp"

#include <cmath>
#include <stdexcept>

#include "embedded_json.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/sequence_pattern.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/sky_ranges.hpp"

namespace nimbus::volume {
namespace {

using json = nlohmann::json;

[[noreturn]] void bad(const std::string& message) { throw std::invalid_argument(message); }

double number(const json& v, const std::string& key, double lo, double hi) { return json_number(v, key, lo, hi); }
glm::dvec3 vec3(const json& v, const std::string& key, double limit) { return json_vec3(v, key, limit); }

constexpr double kMaxPosition = 1.0e6;  // metres from the origin
constexpr double kMaxWind = 200.0;      // metres per second

SkyCloud cloud_from(const json& c, const std::string& where) {
  if (!c.is_object()) bad(where + " must be an object");
  SkyCloud out;
  bool has_preset = false;
  for (const auto& [k, v] : c.items()) {
    const std::string key = where + "." + echo(k);  // a key read from a file: short, one line
    if (k == "preset") {
      if (!v.is_string()) bad(key + " must be a preset name");
      out.preset = v.get<std::string>();
      try {
        load_preset(out.preset);  // unknown -> invalid_argument listing the known ones
      } catch (const std::invalid_argument& e) {
        bad(key + ": " + e.what());
      }
      has_preset = true;
    } else if (k == "file") {
      if (!v.is_string() || v.get<std::string>().empty()) bad(key + " must be a VDB file or a name.%04d.vdb pattern");
      out.file = v.get<std::string>();
      SequencePattern::parse(out.file, key);  // one %d or %0Nd frame field at most, named by its key
    } else if (k == "grid") {
      if (!v.is_string()) bad(key + " must be a grid name");
      out.grid = v.get<std::string>();
    } else if (k == "up") {
      if (!v.is_string() || (v != "auto" && v != "y" && v != "z")) bad(key + " must be auto, y or z");
      out.up = v.get<std::string>();
    } else if (k == "position") {
      out.position_m = vec3(v, key, kMaxPosition);
    } else if (k == "seed") {
      out.seed = static_cast<uint32_t>(number(v, key, 0, 4294967295.0));
      if (static_cast<double>(out.seed) != v.get<double>()) bad(key + " must be a whole number");
    } else if (k == "overrides") {
      if (!v.is_object()) bad(key + " must be an object of preset cloud keys");
      out.overrides = v;
    } else {
      bad(key + ": unknown key (known: preset, file, grid, up, position, seed, overrides)");
    }
  }
  if (has_preset == !out.file.empty()) bad(where + " needs exactly one of preset and file");
  if (!out.file.empty() && !out.overrides.empty()) bad(where + ".overrides: only a preset cloud has them");
  return out;
}

}  // namespace

void validate(const Sky& s) {
  if (s.clouds.empty()) bad("sky clouds: at least one cloud is needed");
  for (std::size_t i = 0; i < s.clouds.size(); ++i)
    if (s.clouds[i].file.empty()) sky_cloud_params(s, i);  // names the bad one
  const glm::dvec3 w = s.wind_m_s;
  if (!(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z)) || std::abs(w.x) > kMaxWind ||
      std::abs(w.y) > kMaxWind || std::abs(w.z) > kMaxWind)
    bad("sky wind: each component must be finite and within +-200 m/s");
  if (!(s.evolution_scale >= 0.0 && s.evolution_scale <= 1000.0)) bad("sky evolution: must be in [0, 1000]");
  if (!kSunElevationRangeDeg.holds(s.sun_elevation_deg))
    bad("sky sun.elevation: must be in " + range_text(kSunElevationRangeDeg) + " degrees");
  if (!kSunAzimuthRangeDeg.holds(s.sun_azimuth_deg)) bad("sky sun.azimuth: must be in " + range_text(kSunAzimuthRangeDeg) + " degrees");
  if (!(s.voxel_size_m >= 2.0 && s.voxel_size_m <= 500.0)) bad("sky voxel_size: must be in [2, 500] metres");
  if (!(s.keyframe_interval_s > 0.0 && s.keyframe_interval_s <= 3600.0))
    bad("sky keyframe_interval: must be in (0, 3600] seconds");
}

Sky sky_from_json(const json& doc, const std::string& where) {
  if (!doc.is_object()) bad(where + " must be a JSON object");
  Sky s;
  bool has_clouds = false;
  for (const auto& [k, v] : doc.items()) {
    const std::string key = where + "." + echo(k);  // a key read from a file: short, one line
    if (k == "description") {
      if (!v.is_string()) bad(key + " must be text");
    } else if (k == "clouds") {
      if (!v.is_array() || v.empty()) bad(key + " must be a non-empty array of clouds");
      if (v.size() > 64) bad(key + ": at most 64 clouds, got " + std::to_string(v.size()));
      for (std::size_t i = 0; i < v.size(); ++i) s.clouds.push_back(cloud_from(v[i], key + "[" + std::to_string(i) + "]"));
      has_clouds = true;
    } else if (k == "wind") {
      s.wind_m_s = vec3(v, key, kMaxWind);
    } else if (k == "evolution") {
      s.evolution_scale = number(v, key, 0.0, 1000.0);
    } else if (k == "sun") {
      if (!v.is_object()) bad(key + " must be {\"elevation\": deg, \"azimuth\": deg}");
      for (const auto& [sk, sv] : v.items()) {
        if (sk == "elevation") {
          s.sun_elevation_deg = number(sv, key + ".elevation", kSunElevationRangeDeg.lo, kSunElevationRangeDeg.hi);
        } else if (sk == "azimuth") {
          s.sun_azimuth_deg = number(sv, key + ".azimuth", kSunAzimuthRangeDeg.lo, kSunAzimuthRangeDeg.hi);
          if (s.sun_azimuth_deg == kSunAzimuthRangeDeg.hi) s.sun_azimuth_deg = kSunAzimuthRangeDeg.lo;
        } else {
          bad(key + "." + echo(sk) + ": unknown key (known: elevation, azimuth)");
        }
      }
    } else if (k == "voxel_size") {
      s.voxel_size_m = number(v, key, 2.0, 500.0);
    } else if (k == "keyframe_interval") {
      s.keyframe_interval_s = number(v, key, 1e-3, 3600.0);
    } else {
      bad(key + ": unknown key (known: description, clouds, wind, evolution, sun, voxel_size, keyframe_interval)");
    }
  }
  if (!has_clouds) bad(where + ".clouds is missing");
  try {
    validate(s);
  } catch (const std::invalid_argument& e) {
    bad(where + ": " + e.what());
  }
  return s;
}

json sky_to_json(const Sky& s) {
  json clouds = json::array();
  for (const SkyCloud& c : s.clouds) {
    json o = {{"position", {c.position_m.x, c.position_m.y, c.position_m.z}}, {"seed", c.seed}};
    if (c.file.empty()) {
      o["preset"] = c.preset;
    } else {
      o["file"] = c.file;
      if (!c.grid.empty()) o["grid"] = c.grid;
      o["up"] = c.up;
    }
    if (!c.overrides.empty()) o["overrides"] = c.overrides;
    clouds.push_back(o);
  }
  return {{"clouds", clouds},
          {"wind", {s.wind_m_s.x, s.wind_m_s.y, s.wind_m_s.z}},
          {"evolution", s.evolution_scale},
          {"sun", {{"elevation", s.sun_elevation_deg}, {"azimuth", s.sun_azimuth_deg}}},
          {"voxel_size", s.voxel_size_m},
          {"keyframe_interval", s.keyframe_interval_s}};
}

Sky load_sky_file(const std::string& path) {
  json doc = read_json_file(path, "sky file");
  // A cloud's coverage map named relative to the sky file is found beside it.
  if (doc.is_object() && doc.contains("clouds") && doc["clouds"].is_array())
    for (json& c : doc["clouds"])
      if (c.is_object() && c.contains("overrides") && c["overrides"].is_object() && c["overrides"].contains("coverage_map") &&
          c["overrides"]["coverage_map"].is_string())
        c["overrides"]["coverage_map"] = resolve_beside(c["overrides"]["coverage_map"].get<std::string>(), path);
  return sky_from_json(doc, "sky file '" + path + "'");
}

void save_sky_file(const Sky& sky, const std::string& path) {
  validate(sky);
  write_json_file(path, sky_to_json(sky), "sky file");
}

Sky default_sky() {
  for (std::size_t i = 0; i < kEmbeddedSkiesCount; ++i) {
    if (std::string(kEmbeddedSkies[i].name) == "default")
      return sky_from_json(json::parse(kEmbeddedSkies[i].text), "sky 'default'");
  }
  throw std::logic_error("the default sky is not built in (volume/skies/default.json)");
}

CloudParams sky_cloud_params(const Sky& sky, std::size_t index) {
  if (index >= sky.clouds.size()) throw std::out_of_range("sky cloud index");
  const SkyCloud& c = sky.clouds[index];
  if (!c.file.empty()) throw std::logic_error("sky cloud " + std::to_string(index) + " is a file, not a preset");
  const std::string where = "sky clouds[" + std::to_string(index) + "]";
  json cloud = load_preset(c.preset).at("cloud");
  for (const auto& [k, v] : c.overrides.items()) {
    // Any preset takes a coverage map (cloud_model.hpp), whether or not its file lists the keys.
    const bool map_key = k == "coverage_map" || k == "coverage_map_extent" || k == "coverage_map_height";
    if (!cloud.contains(k) && !map_key) bad(where + ".overrides." + echo(k) + ": preset '" + c.preset + "' has no such key");
    if (cloud[k].is_object() && v.is_object()) {  // a field: its keys one by one
      for (const auto& [kk, vv] : v.items()) {
        if (!cloud[k].contains(kk)) bad(where + ".overrides." + echo(k) + "." + echo(kk) + ": preset '" + c.preset + "' has no such key");
        cloud[k][kk] = vv;
      }
    } else {
      cloud[k] = v;
    }
  }
  CloudParams p = cloud_from_json(cloud, where + " (" + c.preset + ")");
  p.seed = c.seed;
  p.wind = glm::dvec3(0.0);
  p.evolution *= sky.evolution_scale;
  validate(p);
  return p;
}

}  // namespace nimbus::volume
