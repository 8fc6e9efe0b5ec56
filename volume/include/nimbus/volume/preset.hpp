// Presets: named cloud and gas parameter sets shipped as JSON files (volume/presets/*.json,
// built into the binary), with the vocabulary users know (coverage, density, erosion, base
// altitude, thickness, wind). A preset file holds "name", "genus", "description",
// "voxel_size" (metres), "cloud" (the CloudParams, every key documented in "docs") and "docs".
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "nimbus/volume/cloud_model.hpp"

namespace nimbus::volume {

struct PresetInfo {
  std::string name;
  std::string genus;
  std::string description;
};

// The shipped presets, sorted by name: parsed on the first call, the same list after.
const std::vector<PresetInfo>& list_presets();

// The preset's JSON document; throws std::invalid_argument naming an unknown preset (and
// listing the known ones).
nlohmann::json load_preset(std::string_view name);

// CloudParams from a "cloud" object. Every key must be known; a wrong type or range throws
// std::invalid_argument naming the key (prefixed by `where`). A "coverage_map" PNG is read here
// (std::runtime_error naming the file when it cannot be).
CloudParams cloud_from_json(const nlohmann::json& cloud, const std::string& where);

// A preset document's "voxel_size" in metres (25 when absent); std::invalid_argument naming
// `where` unless it is a number in [1e-6, 1e6].
double preset_voxel_size(const nlohmann::json& doc, const std::string& where);
nlohmann::json cloud_to_json(const CloudParams& p);

// --set key=value on a "cloud" object: key is a dot path (coverage, gas.exponent, wind,
// shapes.0.size); value is JSON (a number, [x, y, z], true, "text") or else a plain string.
// The key must exist already. Throws std::invalid_argument naming the key.
void set_key(nlohmann::json& cloud, std::string_view key_eq_value);

// --params FILE: merge a JSON object (the "cloud" keys, or a whole preset document) into a
// preset document. Throws std::invalid_argument naming the file.
// A "coverage_map" given relative to the file is taken relative to the file's directory.
void merge_params_file(nlohmann::json& preset, const std::string& path);

// `file` as named inside the JSON file `json_path`: a relative name is taken relative to that
// file's directory; an absolute or empty one is kept.
std::string resolve_beside(const std::string& file, const std::string& json_path);

}  // namespace nimbus::volume
