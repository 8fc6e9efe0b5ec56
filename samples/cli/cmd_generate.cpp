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
#include "nimbus/base/validate.hpp"
#include "frame_range.hpp"
#include "generate_plan.hpp"
#include "nimbus/app/sequence_path.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/volume/brick.hpp"
#include "nimbus/base/memory.hpp"
#include "outputs.hpp"
#include "progress.hpp"
#include "nimbus/volume/cloud_model.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/sky.hpp"
#include "nimbus/volume/sky_volume.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/voxel_size.hpp"

namespace nimbus::cli {

using app::check_sequence_pattern;
using app::has_frame_field;
using app::sequence_path;
namespace {

struct GenerateArgs {
  std::string preset;
  std::optional<uint32_t> seed;
  std::optional<double> voxel_size;
  std::optional<int> res;
  FrameArgs frame;
  std::string brick;  // "I/N" or "I/AxBxC"
  std::vector<std::string> sets;
  double size = 1.0;
  bool plan_json = false;
  std::string params;
  std::string up = "z";
  bool full_float = false;
  std::string output;
  std::string sky;           // --sky SKY.json: the sky's clouds as one volume
  std::string coverage_map;  // --coverage-map FILE.png
};

// "--brick I/N": the brick's index and the layout text (N or AxBxC); UsageError when malformed.
std::pair<int, std::string> parse_brick(const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,4})/(\d{1,4}(?:x\d{1,4}x\d{1,4})?))")))
    throw UsageError("--brick: '" + echo(text) + "' must be I/N or I/AxBxC (brick I, 0-based, of N; e.g. 3/4 or 3/2x2x1)");
  return {std::stoi(m[1]), m[2]};
}

std::string mib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f MiB", bytes / (1 << 20));
  return buf;
}

// `nimbus generate --sky SKY.json`: every preset cloud of the sky, placed and drifted as the viewer
// shows them at each time, summed into one density grid (sky_volume.hpp).
int run_generate_sky(const GenerateArgs& a) {
  // Flags that choose or change one preset make no sense for a sky (its clouds name their own).
  const std::pair<bool, const char*> refused[] = {{!a.preset.empty(), "--preset"},
                                                  {!a.params.empty(), "--params"},
                                                  {!a.sets.empty(), "--set"},
                                                  {!a.brick.empty(), "--brick"},
                                                  {a.seed.has_value(), "--seed"},
                                                  {a.res.has_value(), "--res"},
                                                  {!a.coverage_map.empty(), "--coverage-map"}};
  for (const auto& [given, flag] : refused)
    if (given)
      throw UsageError(std::string(flag) + ": not with --sky (the sky file names each cloud's preset, seed and "
                                           "overrides; a cloud's coverage map goes in its overrides)");
  if (a.up != "y" && a.up != "z") throw UsageError("--up: '" + a.up + "' must be y or z");
  if (a.voxel_size) {
    try {
      volume::check_voxel_size(*a.voxel_size, "--voxel-size");  // the one range of voxel sizes
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  const FrameRange range = parse_frames(a.frame);
  check_sequence_pattern("-o", a.output);
  if (!range.sequence && has_frame_field(a.output))
    throw UsageError("-o: '" + echo(a.output) + "' holds a frame field but no --frames was given");
  volume::Sky sky;
  try {
    sky = volume::load_sky_file(a.sky);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--sky: ") + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("--sky: ") + e.what());
  }
  const double vs = a.voxel_size ? *a.voxel_size : sky.voxel_size_m;
  // Sizes that would exhaust memory are refused before any voxel, at the first and last frame.
  for (const int frame : {range.first, range.last}) {
    const double t = range.time(frame);
    uint64_t dense = 0;
    try {
      dense = volume::sky_dense_voxels(sky, vs, t);
    } catch (const std::invalid_argument& e) {
      throw UsageError("--sky " + a.sky + ": at " + time_text(t) + ": " + e.what());
    }
    ensure_fits_in_memory(dense, sizeof(float), "the sky's clouds' bounding boxes at voxel size " + number_text(vs) + " m");
  }
  std::vector<PathArg> outputs;
  for (int frame = range.first; frame <= range.last; ++frame)
    outputs.push_back({"-o", range.sequence ? sequence_path(a.output, frame) : a.output});
  check_outputs(outputs, RunInputs().file("--sky", a.sky).sky(sky, "--sky '" + a.sky + "'"));
  checks_done();

  volume::ExportInfo info;
  info.preset = "sky";
  info.seed = sky.clouds.empty() ? 0 : sky.clouds.front().seed;
  info.up_axis = a.up[0];
  if (range.sequence) info.fps = range.fps;
  info.extra = {{"sky_file", a.sky}, {"sky_clouds", int64_t(sky.clouds.size())}};
  volume::ExportOptions eo;
  eo.half_float = !a.full_float;
  for (int frame = range.first; frame <= range.last; ++frame) {
    const double t = range.time(frame);
    const auto start = std::chrono::steady_clock::now();
    volume::SkyVolumeStats stats;
    const openvdb::FloatGrid::Ptr density = volume::generate_sky_density(sky, vs, t, &stats);
    if (stats.active_voxels == 0)
      throw std::runtime_error("the sky has no voxel of density >= 1e-6 at voxel size " + number_text(vs) + " m; nothing written");
    info.time = t;
    info.frame = range.sequence ? frame : 0;
    const std::string path = range.sequence ? sequence_path(a.output, frame) : a.output;
    volume::write_volume_vdb(path, {density}, info, eo);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s: sky %s, %d clouds, voxel %g m, %lld active voxels, t = %g s, %.2f s\n", path.c_str(),
                a.sky.c_str(), stats.clouds, vs, static_cast<long long>(stats.active_voxels), t, secs);
  }
  return 0;
}

// --plan-json: the plan at the first frame's time, as JSON on stdout (generate_plan.hpp); no file.
int print_plan_json(const GenerateArgs& a, const GeneratePlan& plan, const FrameRange& range, bool brick) {
  if (brick) throw UsageError("--plan-json: the plan is of the whole cloud, not of a --brick");
  if (!a.output.empty()) throw UsageError("--plan-json: writes no file; leave out -o");
  const nlohmann::json j = plan_json(plan, range.time(range.first));
  checks_done();
  std::printf("%s\n", j.dump(2).c_str());
  return 0;
}

int run_generate(const GenerateArgs& a) {
  if (a.output.empty() && !a.plan_json) throw UsageError("-o/--output: an output file is required (or --plan-json)");
  if (!a.sky.empty()) {
    if (a.plan_json) throw UsageError("--plan-json: a plan is of one preset, not of --sky");
    if (a.size != 1.0) throw UsageError("--size: not with --sky (each cloud of the sky has its own size)");
    return run_generate_sky(a);
  }
  if (a.preset.empty()) throw UsageError("--preset: required (or --sky SKY.json for a sky's clouds)");
  if (a.up != "y" && a.up != "z") throw UsageError("--up: '" + a.up + "' must be y or z");
  const FrameRange range = parse_frames(a.frame);
  const int first = range.first, last = range.last;
  const bool sequence = range.sequence;
  check_sequence_pattern("-o", a.output);
  if (!sequence && has_frame_field(a.output))
    throw UsageError("-o: '" + echo(a.output) + "' holds a frame field but no --frames was given");
  std::optional<std::pair<int, std::string>> brick;
  if (!a.brick.empty()) {
    if (sequence) throw UsageError("--brick: a brick is of one time (--time), not of --frames");
    brick = parse_brick(a.brick);
  }

  GenerateRequest request{a.preset, a.seed, a.voxel_size, a.res, a.sets, a.size, a.params, a.coverage_map, nullptr};
  const GeneratePlan plan = plan_generate(request);
  if (a.plan_json) return print_plan_json(a, plan, range, brick.has_value());
  const volume::CloudParams& params = plan.params;
  volume::GenerateOptions opt;
  opt.voxel_size = plan.voxel_size_m;
  // A brick: the field's index box at this time, cut as --brick asks.
  std::optional<volume::BrickTag> tag;
  if (brick) {
    volume::BrickTag t;
    opt.time = range.time(first);
    try {
      t.layout = volume::make_brick_layout(volume::density_index_box(params, opt.voxel_size, range.time(first)), brick->second);
    } catch (const std::invalid_argument& e) {
      char vs[32];
      std::snprintf(vs, sizeof vs, "%g", opt.voxel_size);
      throw UsageError(std::string("--brick: ") + e.what() + " (at voxel size " + vs + " m)");
    }
    if (brick->first >= t.layout.size())
      throw UsageError("--brick: brick " + std::to_string(brick->first) + " of " + t.layout.text() + " does not exist (0-" +
                       std::to_string(t.layout.size() - 1) + ")");
    t.index = brick->first;
    t.half_float = !a.full_float;
    t.field_id = volume::field_identity(params, opt, a.up[0], t.half_float);
    opt.clip = volume::brick_box(t.layout, t.index);
    tag = t;
  }
  // The model at the first and the last frame's time, so that a time it cannot take is refused
  // before any file is written (as generate_density would refuse it at that frame).
  for (const int frame : {first, last}) check_generate_time(plan, range.time(frame));
  if (!tag) {  // a box too large for memory is refused now (and by --check-only), not at its frame
    for (const int frame : {first, last}) {
      try {
        (void)check_generate_memory(plan, range.time(frame));
      } catch (const OutOfMemoryRequest& e) {
        throw OutOfMemoryRequest(std::string(e.what()) + "; cut the field into bricks with --brick I/N (docs/farm.md)");
      }
    }
  }
  std::vector<PathArg> outputs;
  for (int frame = first; frame <= last; ++frame) outputs.push_back({"-o", sequence ? sequence_path(a.output, frame) : a.output});
  // Every file the parameters came from or name, however it was named (--params, --set, the
  // preset, --coverage-map), is an input.
  check_outputs(outputs, RunInputs().file("--params", a.params).file("--coverage-map", a.coverage_map).cloud(params, "cloud"));
  checks_done();
  if (tag) {
    const openvdb::Coord d = opt.clip->dim();
    std::printf("brick %d of %s: index box [%d %d %d .. %d %d %d], %d x %d x %d voxels, at most %s as dense floats\n",
                tag->index, tag->layout.text().c_str(), opt.clip->min().x(), opt.clip->min().y(), opt.clip->min().z(),
                opt.clip->max().x(), opt.clip->max().y(), opt.clip->max().z(), d.x(), d.y(), d.z(),
                mib(double(d.x()) * d.y() * d.z() * sizeof(float)).c_str());
  }

  volume::ExportInfo info;
  info.preset = a.preset;
  info.seed = params.seed;
  info.up_axis = a.up[0];
  if (sequence) info.fps = range.fps;
  // A periodic field says so: renderers draw its copies to the horizon (render/core cloud_source.hpp).
  add_period_metadata(params, info);
  if (tag) {  // a brick's keys after the field's own, which merge keeps
    const volume::Metadata keys = volume::brick_metadata(*tag);
    info.extra.insert(info.extra.end(), keys.begin(), keys.end());
  }
  volume::ExportOptions eo;
  eo.half_float = !a.full_float;

  for (int frame = first; frame <= last; ++frame) {
    const double t = range.time(frame);
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
    } catch (const OutOfMemoryRequest& e) {
      if (tag) throw;
      throw OutOfMemoryRequest(std::string(e.what()) + "; cut the field into bricks with --brick I/N (docs/farm.md)");
    } catch (const std::invalid_argument& e) {  // the parameters passed at time 0: the time is at fault
      throw UsageError("at " + time_text(t) + " (--time, --frames/--fps): " + e.what());
    }
    if (stats.active_voxels == 0 && !tag)
      throw std::runtime_error((sequence ? "frame " + std::to_string(frame) + ": " : std::string()) +
                               "the cloud has no voxel of density >= 1e-6 at voxel size " + number_text(opt.voxel_size) +
                               " m (shapes smaller than a voxel, or coverage, weight or density leave nothing); nothing written");
    std::vector<openvdb::FloatGrid::ConstPtr> grids{density};
    if (auto temperature = volume::generate_temperature(params, *density)) grids.push_back(temperature);
    info.time = t;
    info.frame = sequence ? frame : 0;
    const std::string path = sequence ? sequence_path(a.output, frame) : a.output;
    volume::write_volume_vdb(path, grids, info, eo);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s: %s, voxel %g m, %lld active voxels%s, t = %g s, octaves %d of %d, %.2f s\n",
                path.c_str(), a.preset.c_str(), opt.voxel_size, static_cast<long long>(stats.active_voxels),
                grids.size() > 1 ? " + temperature" : "", t, stats.octaves_used, stats.octaves_requested, secs);
    if (tag)
      std::printf("brick %d of %s: peak memory %s (resident, the whole process)\n", tag->index, tag->layout.text().c_str(),
                  mib(double(peak_resident_bytes())).c_str());
  }
  return 0;
}

}  // namespace

void add_generate_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<GenerateArgs>();
  CLI::App* cmd = app.add_subcommand("generate", "Generate a cloud or gas volume from a preset, as OpenVDB");
  cmd->add_option("--preset", a->preset, "preset name (nimbus presets lists them); or --sky");
  cmd->add_option("--sky", a->sky,
                  "a sky file's preset clouds as one volume, placed and drifted as the viewer shows them at --time "
                  "(overlaps add); not with --preset, --params, --set, --brick, --seed, --res, --coverage-map");
  cmd->add_option("--coverage-map", a->coverage_map,
                  "grey PNG (red channel) stretched over the field's area: 0 no cloud, 1 as without a map "
                  "(docs/volume.md, Coverage maps)");
  cmd->add_option("--seed", a->seed, "random seed (default: the preset's)");
  cmd->add_option("--voxel-size", a->voxel_size, "voxel size in metres (default: the preset's)");
  cmd->add_option("--res", a->res, "voxels across the cloud's largest extent (instead of --voxel-size)");
  add_frame_options(cmd, a->frame, "name.%04d.vdb");
  cmd->add_option("--brick", a->brick,
                  "only brick I (0-based) of N, or of AxBxC along x, y, z: 128-voxel-aligned boxes that nimbus merge "
                  "joins (docs/farm.md)");
  cmd->add_option("--size", a->size,
                  "size factor: the cloud this many times as large about its base centre, its noise with it, and the "
                  "preset's voxel size too (after --set and --params; 0.01-100)")
      ->capture_default_str();
  cmd->add_option("--set", a->sets, "override a parameter: key=value (repeatable; nimbus presets show NAME; positions and winds are Z up: x east, y north)");
  cmd->add_option("--params", a->params, "JSON file of parameter overrides");
  cmd->add_option("--up", a->up, "up axis of the written file: z (Blender, and nimbus's own world) or y (Houdini: the grid is turned)")->capture_default_str();
  cmd->add_flag("--float", a->full_float, "store 32-bit floats (default: half floats)");
  cmd->add_option("-o,--output", a->output, "output .vdb file (required, but with --plan-json)");
  cmd->add_flag("--plan-json", a->plan_json,
                "print the plan as JSON (voxel size, box, memory, the default optics: docs/cli.md) and write nothing");
  cmd->callback([&action, a] { action = [a] { return run_generate(*a); }; });
}

}  // namespace nimbus::cli
