// Preset documents: the shipped JSON files, their mapping to CloudParams, and overrides.
#include "nimbus/volume/preset.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "embedded_json.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/noise/params.hpp"
#include "nimbus/volume/coverage_map.hpp"
#include "nimbus/volume/json_io.hpp"

namespace nimbus::volume {


namespace {

using json = nlohmann::json;

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

json parse(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    bad(source + ": not valid JSON (" + std::string(e.what()) + ")");
  }
}

// "<key>: expected <what>, got null" (or "abc", an array, ...).
[[noreturn]] void expected(const std::string& key, const std::string& what, const json& got) {
  bad(key + ": expected " + what + ", got " + json_value_text(got));
}

double number(const json& j, const std::string& key) {
  if (!j.is_number()) expected(key, "a number", j);
  const double v = j.get<double>();
  if (!std::isfinite(v)) bad(key + " must be finite");
  return v;
}

glm::dvec3 vec3(const json& j, const std::string& key) {
  if (!j.is_array() || j.size() != 3) expected(key, "an array of 3 numbers", j);
  return {number(j[0], key + "[0]"), number(j[1], key + "[1]"), number(j[2], key + "[2]")};
}

const char* kind_name(ShapeKind k) {
  switch (k) {
    case ShapeKind::Ellipsoid: return "ellipsoid";
    case ShapeKind::Capsule: return "capsule";
    case ShapeKind::Slab: return "slab";
    case ShapeKind::Lens: return "lens";
  }
  return "?";
}

Shape shape_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) expected(where, "an object", j);
  // A shape is where gas is: without its kind, centre and size it would be a default 1 m ball at
  // the origin, which at cloud voxel sizes is no voxel at all.
  for (const char* k : {"kind", "center", "size"})
    if (!j.contains(k)) bad(where + "." + k + ": missing (a shape needs kind, center and size)");
  Shape s;
  for (const auto& [k, v] : j.items()) {
    const std::string key = where + "." + echo(k);  // a key read from a file: short, one line
    if (k == "kind") {
      const std::string n = v.is_string() ? v.get<std::string>() : "";
      if (n == "ellipsoid") s.kind = ShapeKind::Ellipsoid;
      else if (n == "capsule") s.kind = ShapeKind::Capsule;
      else if (n == "slab") s.kind = ShapeKind::Slab;
      else if (n == "lens") s.kind = ShapeKind::Lens;
      else expected(key, "ellipsoid, capsule, slab or lens", v);
    } else if (k == "center") s.center = vec3(v, key);
    else if (k == "size") s.size = vec3(v, key);
    else if (k == "end") s.end = vec3(v, key);
    else if (k == "falloff") s.falloff = number(v, key);
    else if (k == "weight") s.weight = number(v, key);
    else if (k == "fade_up") s.fade_up = number(v, key);
    else if (k == "roughness") s.roughness = number(v, key);
    else if (k == "root_taper") s.root_taper = number(v, key);
    else if (k == "roughness_seed") {
      if (!v.is_number_unsigned()) expected(key, "an integer >= 0", v);
      s.roughness_seed = v.get<uint32_t>();
    } else if (k == "rooted" || k == "overshoot") {
      if (!v.is_boolean()) expected(key, "true or false", v);
      (k == "rooted" ? s.rooted : s.overshoot) = v.get<bool>();
    }
    else bad(key + ": unknown key");
  }
  validate(s, where);
  return s;
}

json shape_to_json(const Shape& s) {
  json j = {{"kind", kind_name(s.kind)},
            {"center", {s.center.x, s.center.y, s.center.z}},
            {"size", {s.size.x, s.size.y, s.size.z}},
            {"falloff", s.falloff},
            {"weight", s.weight}};
  if (s.kind == ShapeKind::Capsule) j["end"] = {s.end.x, s.end.y, s.end.z};
  if (s.fade_up > 0) j["fade_up"] = s.fade_up;
  if (s.rooted) j["rooted"] = true;
  if (s.root_taper > 0) j["root_taper"] = s.root_taper;
  if (s.overshoot) j["overshoot"] = true;
  if (s.roughness > 0) {
    j["roughness"] = s.roughness;
    j["roughness_seed"] = s.roughness_seed;
  }
  return j;
}

}  // namespace

const std::vector<PresetInfo>& list_presets() {
  // The presets are compiled in: parsed once per process (the viewer's panel asks every frame).
  static const std::vector<PresetInfo> presets = [] {
    std::vector<PresetInfo> out;
    for (size_t i = 0; i < kEmbeddedPresetsCount; ++i) {
      const json j = parse(kEmbeddedPresets[i].text, std::string("preset ") + kEmbeddedPresets[i].name);
      out.push_back({kEmbeddedPresets[i].name, j.value("genus", ""), j.value("description", "")});
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    return out;
  }();
  return presets;
}

json load_preset(std::string_view name) {
  for (size_t i = 0; i < kEmbeddedPresetsCount; ++i)
    if (name == kEmbeddedPresets[i].name)
      return parse(kEmbeddedPresets[i].text, std::string("preset ") + kEmbeddedPresets[i].name);
  std::string known;
  for (const auto& p : list_presets()) known += (known.empty() ? "" : ", ") + p.name;
  bad("unknown preset '" + echo(name) + "' (known: " + known + ")");
}

glm::dvec2 vec2(const json& j, const std::string& key) {
  if (!j.is_array() || j.size() != 2) expected(key, "an array of 2 numbers", j);
  return {number(j[0], key + "[0]"), number(j[1], key + "[1]")};
}

CloudFieldParams field_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) expected(where, "an object", j);
  CloudFieldParams f;
  for (const auto& [k, v] : j.items()) {
    const std::string key = where + "." + echo(k);  // a key read from a file: short, one line
    if (k == "center") f.center_m = vec2(v, key);
    else if (k == "size") f.size_m = vec2(v, key);
    else if (k == "coverage") f.coverage = number(v, key);
    else if (k == "size_exponent") f.size_exponent = number(v, key);
    else if (k == "min_diameter") f.min_diameter_m = number(v, key);
    else if (k == "max_diameter") f.max_diameter_m = number(v, key);
    else if (k == "depth_scale") f.depth_scale = number(v, key);
    else if (k == "roughness") f.roughness = number(v, key);
    else if (k == "periodic") {
      if (!v.is_boolean()) expected(key, "true or false", v);
      f.periodic = v.get<bool>();
    } else if (k == "seed") {
      if (!v.is_number_unsigned()) expected(key, "an integer >= 0", v);
      f.seed = v.get<uint32_t>();
    } else if (k == "species") {
      if (!v.is_object() || v.empty()) bad(key + " must be an object of species shares, e.g. {\"humilis\": 0.6}");
      f.species.clear();
      for (const auto& [name, share] : v.items()) {
        SpeciesShare s;
        if (!parse_species(name, &s.species)) bad(key + "." + echo(name) + ": unknown species (humilis, mediocris, congestus)");
        s.share = number(share, key + "." + echo(name));
        f.species.push_back(s);
      }
    } else bad(key + ": unknown key");
  }
  validate(f, where);
  return f;
}

json field_to_json(const CloudFieldParams& f) {
  json species = json::object();
  for (const SpeciesShare& s : f.species) species[to_string(s.species)] = s.share;
  return {{"center", {f.center_m.x, f.center_m.y}}, {"size", {f.size_m.x, f.size_m.y}},
          {"coverage", f.coverage}, {"size_exponent", f.size_exponent},
          {"min_diameter", f.min_diameter_m}, {"max_diameter", f.max_diameter_m},
          {"depth_scale", f.depth_scale}, {"roughness", f.roughness}, {"seed", f.seed}, {"species", species},
          {"periodic", f.periodic}};
}

double preset_voxel_size(const json& doc, const std::string& where) {
  if (!doc.is_object() || !doc.contains("voxel_size")) return 25.0;
  return json_number(doc["voxel_size"], where + ": voxel_size", 1e-6, 1e6);
}

CloudParams cloud_from_json(const json& c, const std::string& where) {
  if (!c.is_object()) expected(where, "an object", c);
  CloudParams p;
  for (const auto& [k, v] : c.items()) {
    const std::string key = where + "." + echo(k);  // a key read from a file: short, one line
    if (k == "shapes") {
      if (!v.is_array()) expected(key, "an array of shapes", v);
      for (size_t i = 0; i < v.size(); ++i) p.shapes.push_back(shape_from_json(v[i], key + "[" + std::to_string(i) + "]"));
    } else if (k == "noise") {
      const auto kind = v.is_string() ? noise::parse_kind(v.get<std::string>()) : std::nullopt;
      if (!kind) expected(key, "value, gradient, wavelet or worley", v);
      p.noise = *kind;
    } else if (k == "octaves") {
      if (!v.is_number_integer()) expected(key, "an integer", v);
      p.octaves = v.get<int>();
    } else if (k == "seed") {
      if (!v.is_number_unsigned()) expected(key, "an integer >= 0", v);
      p.seed = v.get<uint32_t>();
    } else if (k == "sine") {
      if (!v.is_boolean()) expected(key, "true or false", v);
      p.gas.sine = v.get<bool>();
    } else if (k == "field") p.field = field_from_json(v, key);
    else if (k == "shear") p.shear = vec2(v, key);
    else if (k == "cauliflower") p.cauliflower = number(v, key);
    else if (k == "cauliflower_frequency") p.cauliflower_frequency = number(v, key);
    else if (k == "stretch") p.stretch = number(v, key);
    else if (k == "stretch_altitude") p.stretch_altitude = number(v, key);
    else if (k == "stretch_direction") p.stretch_direction = vec2(v, key);
    else if (k == "wind") p.wind = vec3(v, key);
    else if (k == "frequency") p.frequency = number(v, key);
    else if (k == "base_altitude") p.base_altitude = number(v, key);
    else if (k == "base_softness") p.base_softness = number(v, key);
    else if (k == "ceiling_altitude") p.ceiling_altitude = number(v, key);
    else if (k == "ceiling_softness") p.ceiling_softness = number(v, key);
    else if (k == "flat_layer") p.flat_layer = number(v, key);
    else if (k == "lacunarity") p.lacunarity = number(v, key);
    else if (k == "gain") p.gain = number(v, key);
    else if (k == "coverage") p.coverage = number(v, key);
    else if (k == "billow") p.billow = number(v, key);
    else if (k == "erosion") p.erosion = number(v, key);
    else if (k == "erosion_frequency") p.erosion_frequency = number(v, key);
    else if (k == "furrows") p.furrows = number(v, key);
    else if (k == "furrow_frequency") p.furrow_frequency = number(v, key);
    else if (k == "displacement") p.displacement = number(v, key);
    else if (k == "displacement_frequency") p.displacement_frequency = number(v, key);
    else if (k == "density") p.gas.max_density = static_cast<float>(number(v, key));
    else if (k == "exponent") p.gas.exponent = static_cast<float>(number(v, key));
    else if (k == "evolution") p.evolution = number(v, key);
    else if (k == "temperature_base") p.temperature_base = number(v, key);
    else if (k == "temperature_height") p.temperature_height = number(v, key);
    else if (k == "period") p.period_m = vec2(v, key);
    else if (k == "coverage_map") {
      if (!v.is_string()) expected(key, "a PNG file name (or \"\" for none)", v);
      p.coverage_map = v.get<std::string>();
    } else if (k == "coverage_map_extent") {
      if (!v.is_array() || (v.size() != 4 && !v.empty())) expected(key, "[west, south, east, north] in metres, or []", v);
      if (v.size() == 4)
        for (int i = 0; i < 4; ++i) p.coverage_map_extent[size_t(i)] = number(v[size_t(i)], key + "[" + std::to_string(i) + "]");
    } else if (k == "coverage_map_height") {
      if (!v.is_boolean()) expected(key, "true or false", v);
      p.coverage_map_height = v.get<bool>();
    } else bad(key + ": unknown key");
  }
  try {
    validate(p);
  } catch (const std::invalid_argument& e) {
    bad(where + ": " + e.what());
  }
  // The map's pixels, read once here (std::runtime_error naming the file) and shared by the models.
  if (!p.coverage_map.empty()) p.coverage_image = read_coverage_png(p.coverage_map);
  return p;
}

json cloud_to_json(const CloudParams& p) {
  json shapes = json::array();
  for (const Shape& s : p.shapes) shapes.push_back(shape_to_json(s));
  json j = {{"base_altitude", p.base_altitude},
          {"base_softness", p.base_softness},
          {"ceiling_altitude", p.ceiling_altitude},
          {"ceiling_softness", p.ceiling_softness},
          {"flat_layer", p.flat_layer},
          {"noise", std::string(noise::to_string(p.noise))},
          {"frequency", p.frequency},
          {"octaves", p.octaves},
          {"lacunarity", p.lacunarity},
          {"gain", p.gain},
          {"coverage", p.coverage},
          {"billow", p.billow},
          {"erosion", p.erosion},
          {"erosion_frequency", p.erosion_frequency},
          {"furrows", p.furrows},
          {"furrow_frequency", p.furrow_frequency},
          {"displacement", p.displacement},
          {"displacement_frequency", p.displacement_frequency},
          {"density", p.gas.max_density},
          {"exponent", p.gas.exponent},
          {"sine", p.gas.sine},
          {"wind", {p.wind.x, p.wind.y, p.wind.z}},
          {"evolution", p.evolution},
          {"seed", p.seed},
          {"temperature_base", p.temperature_base},
          {"temperature_height", p.temperature_height},
          {"cauliflower", p.cauliflower},
          {"cauliflower_frequency", p.cauliflower_frequency},
          {"stretch", p.stretch},
          {"stretch_altitude", p.stretch_altitude},
          {"stretch_direction", {p.stretch_direction.x, p.stretch_direction.y}},
          {"shear", {p.shear.x, p.shear.y}},
          {"shapes", shapes}};
  if (p.field) j["field"] = field_to_json(*p.field);
  if (p.period_m.x > 0) j["period"] = {p.period_m.x, p.period_m.y};
  if (!p.coverage_map.empty()) {
    j["coverage_map"] = p.coverage_map;
    const auto& e = p.coverage_map_extent;
    j["coverage_map_extent"] = e[2] > e[0] ? json{e[0], e[1], e[2], e[3]} : json::array();
    j["coverage_map_height"] = p.coverage_map_height;
  }
  return j;
}

// A JSON null would delete a parameter (merge_patch) or reach a check as a wrong type: refused,
// naming where it is ("--params p.json: cloud.coverage: null is not a value"); `where` ends in ": ".
static void refuse_nulls(const json& j, const std::string& where, const std::string& path = "") {
  if (j.is_null()) bad(where + (path.empty() ? "" : path + ": ") + "null is not a value (give a value, or leave the key out)");
  if (j.is_object())
    for (const auto& [k, v] : j.items()) refuse_nulls(v, where, path.empty() ? echo(k) : path + "." + echo(k));
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) refuse_nulls(j[i], where, path + "[" + std::to_string(i) + "]");
}

void set_key(json& cloud, std::string_view key_eq_value) {
  const size_t eq = key_eq_value.find('=');
  if (eq == std::string_view::npos || eq == 0) bad("--set '" + std::string(key_eq_value) + "': expected key=value");
  const std::string key(key_eq_value.substr(0, eq));
  const std::string text(key_eq_value.substr(eq + 1));
  json value;
  try {
    check_json_depth(text, "--set " + key);
  } catch (const std::runtime_error& e) {
    bad(e.what());
  }
  try {
    value = json::parse(text);
  } catch (const json::exception&) {
    value = text;  // a plain string, e.g. noise=wavelet
  }
  refuse_nulls(value, "--set " + key + ": ");
  json* node = &cloud;
  size_t start = 0;
  while (true) {
    const size_t dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    json* next = nullptr;
    if (node->is_object() && node->contains(part)) {
      next = &(*node)[part];
    } else if (node->is_array()) {
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
      if (!part.empty() && ec == std::errc() && end == part.data() + part.size() && index < node->size())
        next = &(*node)[index];  // an index too large for any array, or for this one, is unknown
    }
    if (!next) bad("--set " + key + ": unknown key '" + part + "'");
    node = next;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  *node = value;
}

void merge_params_file(json& preset, const std::string& path) {
  const std::string where = "--params " + path;  // every refusal starts so (tests/fuzz/fuzz_params.cpp)
  std::string text;
  try {
    text = read_regular_file(path, where);  // a regular file within the size limit
    check_json_depth(text, where);
  } catch (const std::runtime_error& e) {
    bad(e.what());
  }
  const json j = parse(text, where);
  if (!j.is_object()) bad(where + ": must hold a JSON object");
  refuse_nulls(j, where + ": ");
  if (j.contains("cloud") && !j["cloud"].is_object()) expected(where + ": cloud", "an object", j["cloud"]);
  // A whole preset document: its voxel size is read as a number (nimbus generate), so check it here.
  if (j.contains("cloud") && j.contains("voxel_size") &&
      !(j["voxel_size"].is_number() && std::isfinite(j["voxel_size"].get<double>()) && j["voxel_size"].get<double>() > 0))
    expected(where + ": voxel_size", "a number > 0 (metres)", j["voxel_size"]);
  json patch = j;
  // A coverage map named relative to the file is found beside it.
  json& cloud = patch.contains("cloud") ? patch["cloud"] : patch;
  if (cloud.contains("coverage_map") && cloud["coverage_map"].is_string())
    cloud["coverage_map"] = resolve_beside(cloud["coverage_map"].get<std::string>(), path);
  if (patch.contains("cloud")) {
    preset.merge_patch(patch);
  } else {
    preset["cloud"].merge_patch(patch);
  }
}

std::string resolve_beside(const std::string& file, const std::string& json_path) {
  if (file.empty() || file.front() == '/') return file;
  const size_t slash = json_path.rfind('/');
  if (slash == std::string::npos) return file;
  return json_path.substr(0, slash + 1) + file;
}

}  // namespace nimbus::volume
