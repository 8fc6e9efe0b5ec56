// `nimbus generate`: a preset's density volume (and temperature for hot gases) at one time or
// for a range of frames, written as OpenVDB files.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <regex>
#include <tuple>

#include "cli.hpp"
#include "frame_range.hpp"
#include "nimbus/base/memory.hpp"
#include "outputs.hpp"
#include "progress.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::cli {
namespace {

struct GenerateArgs {
  std::string preset;
  std::optional<uint32_t> seed;
  std::optional<double> voxel_size;
  std::optional<int> res;
  std::optional<double> time;
  std::string frames;
  double fps = 24.0;
  bool many_frames = false;
  std::vector<std::string> sets;
  std::string params;
  std::string up = "z";
  bool full_float = false;
  std::string output;
};

// "name.vdb" + frame 12 -> "name.0012.vdb" (the frame number right before the extension).
std::string frame_path(const std::string& out, int frame) {
  const std::string stem = out.size() > 4 && out.substr(out.size() - 4) == ".vdb" ? out.substr(0, out.size() - 4) : out;
  char buf[32];
  std::snprintf(buf, sizeof buf, ".%04d.vdb", frame);
  return stem + buf;
}

int run_generate(const GenerateArgs& a) {
  if (a.output.empty()) throw UsageError("-o: an output file is required");
  if (a.up != "y" && a.up != "z") throw UsageError("--up: '" + a.up + "' must be y or z");
  if (a.voxel_size && a.res) throw UsageError("--voxel-size and --res: give one, not both");
  if (a.voxel_size && !(std::isfinite(*a.voxel_size) && *a.voxel_size > 0))
    throw UsageError("--voxel-size: must be finite and > 0 (metres)");
  if (a.res && (*a.res < 1 || *a.res > 4096)) throw UsageError("--res: must be in [1, 4096]");
  const FrameRange range = parse_frames(a.time, a.frames, a.fps, a.many_frames);
  const int first = range.first, last = range.last;
  const bool sequence = range.sequence;

  nlohmann::json doc;
  try {
    doc = volume::load_preset(a.preset);
    if (!a.params.empty()) volume::merge_params_file(doc, a.params);
    for (const std::string& s : a.sets) volume::set_key(doc["cloud"], s);
    if (a.seed) doc["cloud"]["seed"] = *a.seed;
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  volume::CloudParams params;
  try {
    params = volume::cloud_from_json(doc.at("cloud"), a.preset);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }

  volume::GenerateOptions opt;
  try {
    opt.voxel_size = volume::preset_voxel_size(doc, a.preset);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (a.voxel_size) opt.voxel_size = *a.voxel_size;
  // The model itself refuses what its parameters cannot give (densities beyond the float range).
  const volume::Aabb bounds = volume::CloudModel(params, opt.voxel_size, 0.0).bounds();
  if (a.res) {  // the largest extent of the cloud at time 0 spans `res` voxels
    const glm::dvec3 e = bounds.hi - bounds.lo;
    opt.voxel_size = std::max({e.x, e.y, e.z}) / *a.res;
  }
  std::vector<PathArg> outputs;
  for (int frame = first; frame <= last; ++frame) outputs.push_back({"-o", sequence ? frame_path(a.output, frame) : a.output});
  check_outputs(outputs, {{"--params", a.params}});

  volume::ExportInfo info;
  info.preset = a.preset;
  info.seed = params.seed;
  info.up_axis = a.up[0];
  if (sequence) info.fps = a.fps;
  volume::ExportOptions eo;
  eo.half_float = !a.full_float;

  for (int frame = first; frame <= last; ++frame) {
    const double t = sequence ? frame / a.fps : a.time.value_or(0.0);
    opt.time = t;
    volume::GenerateStats stats;
    const auto start = std::chrono::steady_clock::now();
    Progress progress(a.preset + (sequence ? " frame " + std::to_string(frame) : ""));
    std::mutex m;
    opt.progress = [&](double f) {
      std::lock_guard<std::mutex> lock(m);
      progress.update(f);
    };
    openvdb::FloatGrid::Ptr density;
    try {
      density = volume::generate_density(params, opt, &stats);
    } catch (const OutOfMemoryRequest&) {
      throw;
    } catch (const std::invalid_argument& e) {  // the parameters passed at time 0: the time is at fault
      throw UsageError("at " + time_text(t) + " (--time, --frames/--fps): " + e.what());
    }
    if (stats.active_voxels == 0)
      throw std::runtime_error((sequence ? "frame " + std::to_string(frame) + ": " : std::string()) +
                               "the cloud has no voxel of density >= 1e-6 at voxel size " + std::to_string(opt.voxel_size) +
                               " m (shapes smaller than a voxel, or coverage, weight or density leave nothing); nothing written");
    std::vector<openvdb::FloatGrid::ConstPtr> grids{density};
    if (auto temperature = volume::generate_temperature(params, *density)) grids.push_back(temperature);
    info.time = t;
    info.frame = sequence ? frame : 0;
    const std::string path = sequence ? frame_path(a.output, frame) : a.output;
    volume::write_volume_vdb(path, grids, info, eo);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s: %s, voxel %g m, %lld active voxels%s, t = %g s, octaves %d of %d, %.2f s\n",
                path.c_str(), a.preset.c_str(), opt.voxel_size, static_cast<long long>(stats.active_voxels),
                grids.size() > 1 ? " + temperature" : "", t, stats.octaves_used, stats.octaves_requested, secs);
  }
  return 0;
}

}  // namespace

void add_generate_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<GenerateArgs>();
  CLI::App* cmd = app.add_subcommand("generate", "Generate a cloud or gas volume from a preset, as OpenVDB");
  cmd->add_option("--preset", a->preset, "preset name (nimbus presets lists them)")->required();
  cmd->add_option("--seed", a->seed, "random seed (default: the preset's)");
  cmd->add_option("--voxel-size", a->voxel_size, "voxel size in metres (default: the preset's)");
  cmd->add_option("--res", a->res, "voxels across the cloud's largest extent (instead of --voxel-size)");
  cmd->add_option("--time", a->time, "time in seconds (wind and evolution)");
  cmd->add_option("--frames", a->frames, "frames A-B, written as OUT.%04d.vdb; time = frame / fps");
  cmd->add_option("--fps", a->fps, "frames per second for --frames")->capture_default_str();
  cmd->add_flag("--many-frames", a->many_frames, "allow --frames to span more than 10000 frames");
  cmd->add_option("--set", a->sets, "override a parameter: key=value (repeatable; nimbus presets show NAME)");
  cmd->add_option("--params", a->params, "JSON file of parameter overrides");
  cmd->add_option("--up", a->up, "up axis of the written file: z (Blender) or y (Houdini)")->capture_default_str();
  cmd->add_flag("--float", a->full_float, "store 32-bit floats (default: half floats)");
  cmd->add_option("-o,--output", a->output, "output .vdb file")->required();
  cmd->callback([&action, a] { action = [a] { return run_generate(*a); }; });
}

}  // namespace nimbus::cli
