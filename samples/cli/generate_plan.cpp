// The parameters and voxel size of a generate request (generate_plan.hpp).
#include "generate_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli.hpp"
#include "frame_range.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/volume/cloud_scale.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/voxel_size.hpp"

namespace nimbus::cli {

GeneratePlan plan_generate(const GenerateRequest& r) {
  if (r.voxel_size && r.res) throw UsageError("--voxel-size and --res: give one, not both");
  if (r.voxel_size) {
    try {
      volume::check_voxel_size(*r.voxel_size, "--voxel-size");
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  if (r.res && (*r.res < 1 || *r.res > 4096)) throw UsageError("--res: must be in [1, 4096]");
  try {
    volume::check_size_factor(r.size, "--size");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  GeneratePlan plan;
  try {
    plan.doc = volume::load_preset(r.preset);
    if (!r.params_file.empty()) volume::merge_params_file(plan.doc, r.params_file);
    for (const std::string& s : r.sets) volume::set_key(plan.doc["cloud"], s);
    if (r.seed) plan.doc["cloud"]["seed"] = *r.seed;
    if (!r.coverage_map.empty()) plan.doc["cloud"]["coverage_map"] = r.coverage_map;
    if (r.coverage_image) plan.doc["cloud"].erase("coverage_map");  // the array given in its place
    plan.params = volume::cloud_from_json(plan.doc.at("cloud"), r.preset);
    if (r.coverage_image) {
      plan.params.coverage_image = r.coverage_image;
      volume::validate(plan.params);
    }
    plan.voxel_size_m = volume::preset_voxel_size(plan.doc, r.preset);
    if (r.size != 1.0) {
      plan.params = volume::scale_cloud(plan.params, r.size);
      volume::validate(plan.params);  // a field's diameters, say, may leave their range
      plan.voxel_size_m *= r.size;
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  plan.size = r.size;
  if (r.voxel_size) plan.voxel_size_m = *r.voxel_size;
  // The model itself refuses what its parameters cannot give (densities beyond the float range):
  // std::invalid_argument.
  const volume::Aabb bounds = volume::CloudModel(plan.params, plan.voxel_size_m, 0.0).bounds();
  if (r.res) {  // the largest extent of the cloud at time 0 spans `res` voxels
    const glm::dvec3 e = bounds.hi - bounds.lo;
    plan.voxel_size_m = std::max({e.x, e.y, e.z}) / *r.res;
  }
  return plan;
}

void check_generate_time(const GeneratePlan& plan, double time_s) {
  app::check_sky_time(time_s);  // the one range of times, for the program's --time and Python's time alike
  try {
    (void)volume::CloudModel(plan.params, plan.voxel_size_m, time_s).bounds();
  } catch (const std::invalid_argument& e) {
    throw UsageError("at " + time_text(time_s) + " (--time, --frames/--fps): " + e.what());
  }
}

openvdb::CoordBBox check_generate_memory(const GeneratePlan& plan, double time_s) {
  openvdb::CoordBBox box;
  try {
    box = volume::density_index_box(plan.params, plan.voxel_size_m, time_s);
  } catch (const std::invalid_argument& e) {  // a cloud the time moved beyond the index range
    throw UsageError("at " + time_text(time_s) + " (--time, --frames/--fps): " + e.what());
  }
  if (box.empty()) return box;
  const openvdb::Coord n = box.dim();
  ensure_fits_in_memory(uint64_t(n.x()) * uint64_t(n.y()) * uint64_t(n.z()), sizeof(float),
                        "the cloud's bounding box at this voxel size");
  return box;
}

nlohmann::json plan_json(const GeneratePlan& plan, double time_s) {
  check_generate_time(plan, time_s);
  const openvdb::CoordBBox box = check_generate_memory(plan, time_s);
  const double vs = plan.voxel_size_m;  // voxel (i, j, k) is centred at (i, j, k) * voxel size
  nlohmann::json j;
  j["voxel_size"] = vs;
  j["size"] = plan.size;
  j["time"] = time_s;
  if (box.empty()) {
    j["dims"] = {0, 0, 0};
    j["dense_bytes"] = 0;
    j["bounds_m"] = nullptr;
    j["index_box"] = nullptr;
  } else {
    const openvdb::Coord n = box.dim(), lo = box.min(), hi = box.max();
    j["dims"] = {n.x(), n.y(), n.z()};
    j["dense_bytes"] = uint64_t(n.x()) * uint64_t(n.y()) * uint64_t(n.z()) * sizeof(float);
    j["bounds_m"] = {{lo.x() * vs, lo.y() * vs, lo.z() * vs}, {hi.x() * vs, hi.y() * vs, hi.z() * vs}};
    j["index_box"] = {{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}};
  }
  const render::CloudOptics optics;  // the look's defaults: render/core cloud_optics.hpp
  const render::Phase lobes = render::as_dual_lobes(render::kCloudPhase);
  j["optics"] = {{"extinction_per_m", optics.extinction_per_m},
                 {"albedo", render::kCloudAlbedo},
                 {"phase", {{"g_forward", lobes.g}, {"g_back", lobes.g_back}, {"forward_weight", lobes.forward_weight}}}};
  return j;
}

void add_period_metadata(const volume::CloudParams& params, volume::ExportInfo& info) {
  if (const std::optional<volume::PeriodicTile> tile = volume::periodic_tile(params)) {
    char period[64];
    std::snprintf(period, sizeof period, "%.17g %.17g", tile->size_m.x, tile->size_m.y);
    info.extra.emplace_back(std::string(volume::kPeriodMetadataKey), std::string(period));
  }
}

}  // namespace nimbus::cli
