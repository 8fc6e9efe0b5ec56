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
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::cli {

struct GenerateRequest {
  std::string preset;                // nimbus presets lists them
  std::optional<uint32_t> seed;      // --seed; unset: the preset's
  std::optional<double> voxel_size;  // --voxel-size, metres; unset: the preset's
  std::optional<int> res;            // --res: voxels across the cloud's largest extent at time 0
  std::vector<std::string> sets;     // --set key=value, in order
  double size = 1.0;                 // --size: the cloud this many times as large (volume/cloud_scale.hpp),
                                     // after the overrides; the preset's voxel size with it
  std::string params_file;           // --params FILE (JSON overrides); empty: none
  std::string coverage_map;          // --coverage-map FILE.png; empty: the preset's (none)
  std::shared_ptr<const volume::CoverageImage> coverage_image;  // a map in memory (Python); overrides the file
};

struct GeneratePlan {
  nlohmann::json doc;            // the preset document with the overrides applied
  volume::CloudParams params;    // doc["cloud"], checked, made `size` times as large
  double voxel_size_m = 25.0;
  double size = 1.0;             // the size factor applied
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

// The plan at `time_s` as JSON: what `nimbus generate --plan-json` prints and Python's plan
// returns, so that a program reads it without parsing text. Keys: voxel_size (m), size (the
// factor), time (s), dims (voxels of the box), dense_bytes (the box as dense floats), bounds_m
// ([lo, hi] voxel centres, metres; null for an empty box), index_box ([lo, hi]; null), and optics:
// the look nimbus render gives the cloud where no flag says otherwise (extinction_per_m, albedo,
// phase {g_forward, g_back, forward_weight}; render/core cloud_optics.hpp). The checks of
// check_generate_time and check_generate_memory first, with their errors.
nlohmann::json plan_json(const GeneratePlan& plan, double time_s);

// A periodic field says so in its file: the "period_m" key (volume::kPeriodMetadataKey) with the
// tile's x and y periods, so that renderers draw its copies (render/core cloud_source.hpp).
void add_period_metadata(const volume::CloudParams& params, volume::ExportInfo& info);

}  // namespace nimbus::cli
