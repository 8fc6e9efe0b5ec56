// A sky: several clouds from presets, each placed, seeded and adjusted, drifting on one wind and
// evolving at a common rate, under a sun given by elevation and azimuth. Sky files are JSON
// (volume/skies/default.json is the viewer's default, built into the binary); docs/viewer.md
// documents every key. Z is up, x east, y north; metres and seconds.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "nimbus/volume/cloud_model.hpp"

namespace nimbus::volume {

struct SkyCloud {
  std::string preset;             // a shipped preset (list_presets)
  glm::dvec3 position_m{0.0};     // where the preset's own origin goes
  uint32_t seed = 0;
  nlohmann::json overrides = nlohmann::json::object();  // preset "cloud" keys (coverage, density, ...)
};

struct Sky {
  std::vector<SkyCloud> clouds;         // at least one
  glm::dvec3 wind_m_s{0.0};             // one wind for every cloud (the presets' own winds are ignored)
  double evolution_scale = 1.0;         // multiplies each preset's evolution rate, >= 0
  double sun_elevation_deg = 35.0;      // [-10, 90]
  double sun_azimuth_deg = 120.0;       // clockwise from north, [0, 360)
  double voxel_size_m = 30.0;           // generation resolution, [2, 500]
  double keyframe_interval_s = 30.0;    // sky time between evolution keyframes, (0, 3600]
};

// Throws std::invalid_argument naming `where` and the key (unknown keys, wrong types, ranges,
// unknown presets, bad overrides).
Sky sky_from_json(const nlohmann::json& doc, const std::string& where);
nlohmann::json sky_to_json(const Sky& sky);
void validate(const Sky& sky);

// A sky file; std::runtime_error naming the file when it cannot be read or parsed, and
// std::invalid_argument naming it for bad contents. Saving writes atomically.
Sky load_sky_file(const std::string& path);
void save_sky_file(const Sky& sky, const std::string& path);

// The shipped default sky (volume/skies/default.json).
Sky default_sky();

// One cloud's model parameters: its preset with the overrides and seed, no wind (the drift is a
// translation by wind * t applied at render time, exactly what the wind term of the model does),
// and the evolution rate scaled. Shapes stay at the preset's origin; position_m is applied by
// moving the generated grid. std::invalid_argument naming the cloud's index for bad overrides.
CloudParams sky_cloud_params(const Sky& sky, std::size_t index);

}  // namespace nimbus::volume
