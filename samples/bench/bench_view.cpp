// `nimbus bench view`: the viewer's frame times along a scripted orbit and a time-lapse of the
// default sky, with the adaptive quality's choices and what they cost in error against the
// full-quality frame of the same state, the keyframes' generation time and the longest frame
// while one was made. Headless (EGL); the same Viewer code as `nimbus view`.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "cli/outputs.hpp"
#include "cli/render_args.hpp"
#include "bench_view_accumulated.hpp"
#include "bench_view_path.hpp"
#include "gl_limits.hpp"
#include "nimbus/render/sky/grain_filter.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/core/image_resample.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "viewer/viewer.hpp"

namespace nimbus::cli {
namespace {

struct BenchViewArgs {
  std::string sizes = "640x360,1280x720";
  int frames = 60;
  double budget_ms = 100.0;
  double repeat_to_m = -1.0;  // < 0: the view state's (32 km)
  int error_every = 3;   // compare every Nth adaptive frame with the full-quality frame
  std::string strip;     // a PNG strip of the time-lapse
  int still_samples = 64;  // the still view's progressive samples measured (0: not measured)
  std::string paths;       // path names to run (as the table names them), separated by '|'; empty: all
};

// The paths' names, as the table prints them; --paths takes them separated by '|'.
const std::string kPathNames[] = {"orbit", "orbit, octaves", "orbit, temporal", "time-lapse", "time-lapse, temporal", "sun drag"};

std::vector<std::string> split_paths(const std::string& paths) {
  std::vector<std::string> out;
  if (paths.empty()) return out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = paths.find('|', start);
    out.push_back(paths.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return out;
    start = end + 1;
  }
}

bool path_chosen(const std::string& paths, const std::string& name) {
  const std::vector<std::string> names = split_paths(paths);
  return names.empty() || std::find(names.begin(), names.end(), name) != names.end();
}

using Clock = std::chrono::steady_clock;

std::string levels_text(const std::map<int, int>& levels, bool temporal) {
  std::ostringstream o;
  for (const auto& [l, n] : levels) {
    const viewer::QualityLevel& q = (temporal ? viewer::kTemporalQualityLevels : viewer::kQualityLevels)[l];
    if (o.tellp() > 0) o << ", ";
    o << "x" << q.render_scale << "/" << q.slice_share;
    if (q.light_share < 1.0) o << "/light " << q.light_share;
    o << ": " << n;
  }
  return o.str();
}

// A still view's progressive samples (progressive_frame.hpp): the mean's error against the
// 4x-supersampled frame (twice the size each way, 2x2 boxes, itself the mean of 16 samples)
// after 1, 2, 4, ... samples, and the time they took; and the error of what the viewer shows of
// it, the mean filtered of its grain (still_picture, grain_filter.hpp).
void print_still_view(const render::ViewState& start, const viewer::ViewerOptions& options,
                      const std::vector<std::pair<int, int>>& sizes, int samples) {
  std::printf("\n## A still view's samples on the default view (time paused): the mean against the 4x-supersampled frame\n\n");
  std::printf("| size | samples | rel. RMSE vs 4x supersampled | median rel. | shown (grain filter): rel. RMSE | "
              "time for them, s |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  for (const auto& [w, h] : sizes) {
    viewer::Viewer v(start, options);
    v.state().paused = true;
    v.draw(w, h, 0.0);
    render::ProgressiveFrame fine;
    for (unsigned i = 0; i < 16; ++i)
      fine.add(v.render_at(2 * w, 2 * h, render::FrameQuality{1.0, 0, render::progressive_sample(i)}), "fine");
    const render::Image reference = render::box_downsample(fine.mean(), 2);
    render::ProgressiveFrame mean;
    render::PixelDepths depths;
    double seconds = 0.0;
    for (int i = 0; i < samples; ++i) {
      const auto t0 = Clock::now();
      mean.add(v.render_at(w, h, render::FrameQuality{1.0, 0, render::progressive_sample(static_cast<unsigned>(i))}, &depths),
               "still");
      seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      const int n = i + 1;
      if ((n & (n - 1)) == 0 || n == samples) {
        const render::ImageError e = render::compare_images(mean.mean(), reference);
        const render::Image shown =
            render::still_picture(mean.mean(), mean.samples(), depths, v.state().grain_filter, v.state().slices.jitter);
        std::printf("| %dx%d | %d | %.4f | %.4f | %.4f | %.1f |\n", w, h, n, e.rel_rmse, e.median_rel,
                    render::compare_images(shown, reference).rel_rmse, seconds);
        std::fflush(stdout);
      }
    }
  }
}

// Each pass's time against the device's limit for its fragments (gl_limits.hpp, measured in the
// same run at the same size): the slices and the light buffer blend every fragment, the other
// passes write theirs. Rows: the median frame's fragments (millions), the time they would take
// at the limit, and the pass's time as a multiple of it. A pass far above 1x spends its time
// beyond filling pixels (docs/viewer.md, "The frame's limit", says where it was looked for).
template <class Rows>
void print_pass_limits(const Rows& rows) {
  if (rows.empty()) return;
  bool counted = false;
  for (const auto& row : rows)
    for (const auto& [pass, fragments] : row.result.pass_fragments)
      for (double f : fragments) counted = counted || f >= 0.0;
  std::printf("\n## Each pass against the device's limit for its fragments (%s)\n\n", rows.front().limits.device.c_str());
  if (!counted) {
    std::printf("The driver does not count fragment shader invocations (GL_ARB_pipeline_statistics_query).\n");
    return;
  }
  std::printf("Limits measured in this run (`nimbus bench gl`), M/s: ");
  std::map<std::pair<int, int>, bool> shown;
  for (const auto& row : rows) {
    const GlLimits& l = row.limits;
    if (shown[{l.width, l.height}]) continue;
    shown[{l.width, l.height}] = true;
    std::printf("%dx%d: %.0f shaded, %.0f blended, %.0f 3D samples, %.0f read back; ", l.width, l.height,
                l.fragments_per_s * 1e-6, l.blended_per_s * 1e-6, l.samples_3d_per_s * 1e-6, l.readback_pixels_per_s * 1e-6);
  }
  std::printf("\n\n| size | path | quality | pass | median ms | fragments (M) | ms at the fill limit | multiple of the limit |\n");
  std::printf("|---|---|---|---|---:|---:|---:|---:|\n");
  for (const auto& row : rows) {
    for (const char* pass : kPasses) {
      const auto it = row.result.pass_fragments.find(pass);
      if (it == row.result.pass_fragments.end()) continue;
      const double fragments = percentile(it->second, 0.5), ms = percentile(row.result.pass_ms.at(pass), 0.5);
      if (!(fragments > 0.0)) continue;
      const bool blends = std::string(pass) == "cloud slices" || std::string(pass) == "cloud light";
      const double limit_ms = 1e3 * fragments / (blends ? row.limits.blended_per_s : row.limits.fragments_per_s);
      std::printf("| %s | %s | %.1f | %.2f | %.2f | %.1fx |\n", row.name.c_str(), pass, ms, fragments * 1e-6, limit_ms,
                  ms / std::max(limit_ms, 1e-9));
    }
  }
}

// Bad flags are usage errors, before any GL work (--sizes is checked where it is parsed).
void check_args(const BenchViewArgs& a) {
  if (a.frames < 5 || a.frames > 100000) throw UsageError("--frames: must be in [5, 100000]");
  if (a.still_samples < 0 || a.still_samples > 4096) throw UsageError("--still-samples: must be in [0, 4096]");
  if (!(a.budget_ms > 0.0)) throw UsageError("--budget-ms: must be > 0");
  if (!(a.repeat_to_m <= 1e6)) throw UsageError("--repeat-to: must be in [0, 1e6] metres");
  for (const std::string& name : split_paths(a.paths))
    if (std::find(std::begin(kPathNames), std::end(kPathNames), name) == std::end(kPathNames))
      throw UsageError("--paths: unknown path '" + name + "' (known: orbit|orbit, octaves|orbit, temporal|time-lapse|"
                       "time-lapse, temporal|sun drag)");
  check_outputs({{"--strip", a.strip}});
}

// The state every path starts from: the default view, its periodic tiles as asked.
render::ViewState start_state(const BenchViewArgs& a) {
  render::ViewState s = render::default_view_state();
  if (a.repeat_to_m >= 0.0) s.slices.repeat_to_m = a.repeat_to_m;
  return s;
}

// What the run measures, and the paths table's header.
void print_header(const render::ViewState& start, const BenchViewArgs& a, const std::string& renderer) {
  std::printf("# nimbus bench view: the default sky (%zu clouds, %.0f m voxels, keyframes every %.0f s of sky time), %s\n",
              start.sky.clouds.size(), start.sky.voxel_size_m, start.sky.keyframe_interval_s, renderer.c_str());
  char ms[128];
  if (start.slices.multiple.method == render::MultipleScatteringMethod::LightVolume)
    std::snprintf(ms, sizeof ms, "light volume (%d cells, %lld photons; %d octaves before the first)", start.slices.multiple.light_volume.resolution,
                  static_cast<long long>(start.slices.multiple.light_volume.photons), start.slices.multiple.octaves);
  else
    std::snprintf(ms, sizeof ms, "%d octaves", start.slices.multiple.octaves);
  std::printf("# full quality: %d slices, light %d^2, shafts %s, cloud shadow %d^2, %s, periodic tiles to %.0f m; adaptive budget %.0f ms\n",
              start.slices.slices, start.slices.light_res, render::to_string(start.shafts).c_str(), start.cloud_shadow_res, ms,
              start.slices.repeat_to_m, a.budget_ms);
  std::printf("# orbit: 1.8 deg of tumble per frame, sky time x10; time-lapse: still camera, sky time x30; real time steps\n");
  std::printf("# frame = the viewer's whole frame on the CPU (render, readback); error = rel. RMSE of the adaptive frame,\n");
  std::printf("#   upscaled as the display does, against the full-quality frame of the same state (one frame in %d)\n\n",
              a.error_every);
  std::printf("| size | path | quality | frames | median ms | p95 ms | max ms | fps (median) | frames per level (scale/slices) | "
              "error median / max | keyframes made (s each) | frames held | longest frame while generating | "
              "light volumes made (s each) | frames: stale volume / octaves |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---|---|---|---:|---:|---|---|\n");
}

// A row of the paths table: a path, with or without adaptive quality, the light volume or the octaves.
struct Row {
  Path path;
  bool adaptive;
  const char* name;
  bool octaves = false;  // the octaves instead of the light volume: what the volume costs
  bool temporal = false; // the moving frames accumulated (ViewerOptions::temporal)
};
const Row kRows[] = {Row{Path::Orbit, false, "orbit"}, Row{Path::Orbit, false, "orbit, octaves", true},
                     Row{Path::Orbit, true, "orbit"}, Row{Path::Orbit, true, "orbit, temporal", false, true},
                     Row{Path::TimeLapse, true, "time-lapse"}, Row{Path::TimeLapse, true, "time-lapse, temporal", false, true},
                     Row{Path::SunDrag, true, "sun drag", false, true}};

// The row's line, and the sun drag's and the accumulation's lines under it.
void print_row(const Row& row, const PathResult& r, int frames, int w, int h) {
  const double med = percentile(r.ms, 0.5);
  char err[64] = "-";
  if (!r.errors.empty())
    std::snprintf(err, sizeof err, "%.4f / %.4f", percentile(r.errors, 0.5), *std::max_element(r.errors.begin(), r.errors.end()));
  char kf[64] = "0";
  if (r.keyframes > 0) std::snprintf(kf, sizeof kf, "%lld (%.2f s)", static_cast<long long>(r.keyframes), r.keyframe_s / r.keyframes);
  char gen[32] = "-";
  if (r.longest_generating > 0) std::snprintf(gen, sizeof gen, "%.0f ms", r.longest_generating);
  char lv[64] = "0";
  if (r.volumes > 0) std::snprintf(lv, sizeof lv, "%lld (%.2f s)", static_cast<long long>(r.volumes), r.volume_s / r.volumes);
  std::printf("| %dx%d | %s | %s | %d | %.0f | %.0f | %.0f | %.1f | %s | %s | %s | %d | %s | %s | %d / %d |\n", w, h, row.name,
              row.adaptive ? "adaptive" : "full (anchor)", frames, med, percentile(r.ms, 0.95),
              *std::max_element(r.ms.begin(), r.ms.end()), 1000.0 / med, levels_text(r.levels, row.temporal).c_str(), err,
              kf, r.held, gen, lv, r.stale, r.stand_in);
  if (row.path == Path::SunDrag) {
    const auto text = [](const std::vector<double>& xs) {
      char t[64] = "never";
      if (!xs.empty()) std::snprintf(t, sizeof t, "%.0f ms median, %.0f ms max", percentile(xs, 0.5), *std::max_element(xs.begin(), xs.end()));
      return std::string(t);
    };
    std::printf("|  | sun drag: %zu drags of %d steps of %.0f deg | new sun's first volume on screen: %s (%d frames "
                "with its preview) | its full volume: %s | | | | | | | | | | | |\n",
                r.sun_first_ms.size(), kDragSteps, kDragStepDeg, text(r.sun_first_ms).c_str(), r.preview,
                text(r.sun_full_ms).c_str());
  }
  if (!r.temporal_ms.empty())
    std::printf("|  | %s: the accumulation (TemporalFrame::add, CPU) %.1f ms median of the frame | | | | | | | | | | | | | |\n",
                row.name, percentile(r.temporal_ms, 0.5));
  std::fflush(stdout);
}

struct PassRow {
  std::string name;
  PathResult result;
  GlLimits limits;
};

// Every chosen row at every size, printed as it is measured; their pass times for the tables after.
std::vector<PassRow> run_rows(const BenchViewArgs& a, const std::vector<std::pair<int, int>>& sizes, const render::ViewState& start,
                              const viewer::ViewerOptions& options) {
  std::vector<PassRow> pass_rows;
  for (const auto& [w, h] : sizes) {
    const GlLimits limits = measure_gl_limits(w, h);  // the device's rates at this size, this run
    for (const Row& row : kRows) {
      if (!path_chosen(a.paths, row.name)) continue;
      if (row.path == Path::SunDrag && start.slices.multiple.method != render::MultipleScatteringMethod::LightVolume) continue;
      if (row.octaves && start.slices.multiple.method == render::MultipleScatteringMethod::Octaves) continue;
      render::ViewState state = start;
      if (row.octaves) state.slices.multiple.method = render::MultipleScatteringMethod::Octaves;
      viewer::ViewerOptions row_options = options;
      row_options.temporal = row.temporal;
      viewer::Viewer v(state, row_options);
      v.adaptive().budget_ms = a.budget_ms;
      v.draw(w, h, 0.0);  // the first pair and every program, before timing
      const PathResult r = run_path(v, row.path, w, h, a.frames, row.adaptive, a.error_every);
      print_row(row, r, a.frames, w, h);
      char name[96];
      std::snprintf(name, sizeof name, "%dx%d | %s | %s", w, h, row.name, row.adaptive ? "adaptive" : "full (anchor)");
      pass_rows.push_back({name, r, limits});
    }
  }
  return pass_rows;
}

// Where the GPU's time goes, pass by pass: what a faster device changes.
void print_pass_times(const std::vector<PassRow>& pass_rows, const std::string& renderer) {
  std::printf("\n## GPU time per pass, median ms per frame, on %s (%s)\n\n", renderer.c_str(),
              pass_rows.empty() ? "-" : pass_rows.front().result.timing.c_str());
  std::printf("| size | path | quality |");
  for (const char* p : kPasses) std::printf(" %s |", p);
  std::printf("\n|---|---|---|");
  for (std::size_t i = 0; i < std::size(kPasses); ++i) std::printf("---:|");
  std::printf("\n");
  for (const PassRow& row : pass_rows) {
    std::printf("| %s |", row.name.c_str());
    for (const char* p : kPasses) std::printf(" %.1f |", percentile(row.result.pass_ms.at(p), 0.5));
    std::printf("\n");
  }
  print_pass_limits(pass_rows);
}

// Every level on one still state: what it costs and what it gives up.
void print_levels(const render::ViewState& start, const viewer::ViewerOptions& options,
                  const std::vector<std::pair<int, int>>& sizes) {
  std::printf("\n## The adaptive quality's levels on the default view (time paused; best of 3 frames)\n\n");
  std::printf("| size | level | render scale | slices | frame ms | speed-up | rel. RMSE vs full quality |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [w, h] : sizes) {
    viewer::Viewer v(start, options);
    v.state().paused = true;
    v.draw(w, h, 0.0);
    const render::Image full = v.full_quality_frame(w, h);
    double full_ms = 0.0;
    for (int l = 0; l < viewer::kQualityLevelCount; ++l) {
      render::FrameQuality q = viewer::level_quality(viewer::kQualityLevels[l], start.slices.slices, start.slices.light_res);
      double best = 1e300;
      render::Image img;
      for (int rep = 0; rep < 3; ++rep) {
        const auto t0 = Clock::now();
        img = v.render_at(w, h, q);
        best = std::min(best, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      }
      if (l == 0) full_ms = best;
      std::printf("| %dx%d | %d | %.2f | %d | %.0f | %.1fx | %.4f |\n", w, h, l, q.render_scale, q.slices, best,
                  full_ms / best, render::compare_images(render::upscale_bilinear(img, w, h), full).rel_rmse);
    }
  }
}

// Six frames of the time-lapse, 30 s of sky time apart, exactly their states (keyframes waited).
void write_strip(const render::ViewState& start, viewer::ViewerOptions options, const std::string& path) {
  options.wait_for_keyframes = true;
  viewer::Viewer v(start, options);
  v.adaptive().enabled = false;
  v.state().speed = 30.0;
  const int fw = 320, fh = 180, n = 6;
  render::Image strip(fw * n, fh);
  for (int i = 0; i < n; ++i) {
    if (i > 0) v.advance(1.0);
    const render::Image& f = v.draw(fw, fh, 0.0);
    for (int y = 0; y < fh; ++y)
      for (int x = 0; x < fw; ++x)
        for (int c = 0; c < 4; ++c) strip.pixel(i * fw + x, y)[c] = f.pixel(x, y)[c];
  }
  render::PreviewOptions po;
  po.exposure_stops = start.exposure_stops;
  render::write_png_preview(path, strip, po);
  std::printf("\nstrip: %s (6 frames, 30 s of sky time apart)\n", path.c_str());
}

int run_bench_view(const BenchViewArgs& a) {
  const std::vector<std::pair<int, int>> sizes = parse_resolutions("--sizes", a.sizes);
  check_args(a);
  const auto gl = render::GlContext::create_headless();
  const render::ViewState start = start_state(a);
  const viewer::ViewerOptions options;
  print_header(start, a, gl->renderer());
  print_pass_times(run_rows(a, sizes, start, options), gl->renderer());
  print_levels(start, options, sizes);
  print_accumulated_levels(start, options, sizes);
  print_accumulated_motion(start, sizes);
  if (a.still_samples > 0) print_still_view(start, options, sizes, a.still_samples);
  if (!a.strip.empty()) write_strip(start, options, a.strip);
  return 0;
}

}  // namespace

void add_bench_view(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchViewArgs>();
  CLI::App* cmd = bench.add_subcommand("view", "The viewer: frame times along an orbit and a time-lapse, adaptive quality against its error");
  cmd->add_option("--sizes", a->sizes, "Comma-separated frame sizes WxH")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Frames per path")->capture_default_str();
  cmd->add_option("--budget-ms", a->budget_ms, "Adaptive quality's frame budget while moving")->capture_default_str();
  cmd->add_option("--repeat-to", a->repeat_to_m,
                  "How far the periodic field's tile is repeated from the eye, metres (default: the view state's 32000; 0: one tile)");
  cmd->add_option("--error-every", a->error_every, "Measure the error of every Nth adaptive frame (0: never)")
      ->capture_default_str();
  cmd->add_option("--paths", a->paths, "Only these paths, by the table's names separated by '|' (e.g. 'orbit|orbit, temporal')");
  cmd->add_option("--strip", a->strip, "Also write a PNG strip of six time-lapse frames here");
  cmd->add_option("--still-samples", a->still_samples,
                  "A still view's progressive samples whose mean is measured against the 4x-supersampled frame (0: skip)")
      ->capture_default_str();
  cmd->callback([&action, a] { action = [a] { return run_bench_view(*a); }; });
}

}  // namespace nimbus::cli
