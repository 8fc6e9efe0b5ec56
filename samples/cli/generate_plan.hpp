// What `nimbus generate` makes of a preset and its flags, before any voxel: the parameters with
// every override applied and the voxel size, each bad value a UsageError naming its flag. Shared
// by the command and the Python module, so that both make the same voxels from the same request.
#pragma once
#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "nimbus/volume/cloud_model.hpp"

namespace nimbus::cli {

struct GenerateRequest {
  std::string preset;                // nimbus presets lists them
  std::optional<uint32_t> seed;      // --seed; unset: the preset's
  std::optional<double> voxel_size;  // --voxel-size, metres; unset: the preset's
  std::optional<int> res;            // --res: voxels across the cloud's largest extent at time 0
  std::vector<std::string> sets;     // --set key=value, in order
  std::string params_file;           // --params FILE (JSON overrides); empty: none
  std::string coverage_map;          // --coverage-map FILE.png; empty: the preset's (none)
  std::shared_ptr<const volume::CoverageImage> coverage_image;  // a map in memory (Python); overrides the file
};

struct GeneratePlan {
  nlohmann::json doc;            // the preset document with the overrides applied
  volume::CloudParams params;    // doc["cloud"], checked
  double voxel_size_m = 25.0;
};

// UsageError for a bad flag, an unknown preset or key, a bad value, or both --voxel-size and --res;
// std::invalid_argument when the model refuses the parameters (densities beyond the float range).
GeneratePlan plan_generate(const GenerateRequest& request);

// A time outside the one range of sky times (volume::kSkyTimeRangeS): UsageError "--time: t = ...
// is outside ..." (app::check_sky_time); the model at `time_s` (what generate_density would refuse
// at that time: a cloud moved beyond the noise's range): UsageError "at t = ... s (--time,
// --frames/--fps): ...".
void check_generate_time(const GeneratePlan& plan, double time_s);

// The cloud's index box at `time_s` (what generate_density fills), which as dense floats must fit
// in memory (generate_density's own check, made before any work): nimbus::OutOfMemoryRequest
// naming the box otherwise; UsageError "at t = ..." when the time moves the cloud beyond the index
// range.
openvdb::CoordBBox check_generate_memory(const GeneratePlan& plan, double time_s);

}  // namespace nimbus::cli
