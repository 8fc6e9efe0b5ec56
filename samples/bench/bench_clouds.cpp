// `nimbus bench clouds`: speed against error of the half-angle slice renderer on the noisy sphere
// (nimbus::app's bench_noisy_sphere). Every slice count and light-buffer size renders the same
// volume, camera and light (front-lit and back-lit); its frame time is set beside its error
// against the CPU single-scattering reference, with OpenVDB's vdb_render (defaults, -gain 0) on
// the same VDB as the anchor measured in the same run; then the optional terms one at a time
// (blur, ambient, multiple scattering, jitter), the popping sweep through the branch switch, and
// the same for lamps (bench_clouds_lamps.cpp: point lights near and far, two at once, and the
// steam under a lamp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>

#include <unistd.h>

#include "bench_clouds.hpp"
#include "cli/cli.hpp"
#include "cli/outputs.hpp"
#include "cli/render_args.hpp"
#include "nimbus/app/bench_clouds_scene.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/svg_plot.hpp"

namespace nimbus::cli {
namespace {

using namespace bench_clouds;
using app::bench_camera;
using app::bench_light;
using app::bench_noisy_sphere;
using app::bench_optics;
using app::kBenchAbsorbPerVoxel;
using app::kBenchScatterPerVoxel;
using app::run_vdb_render;
using app::VdbRenderRun;
using render::Plot;
using render::PlotSeries;

// The flags, checked and parsed before any work.
struct CloudsPlan {
  int width = 0, height = 0;
  std::vector<int> slice_counts, light_sizes;
  std::vector<bool> back_lit;
  double ref_view = 0.0, ref_shadow = 0.0;  // the reference's steps, voxels
};

CloudsPlan check_args(const BenchCloudsArgs& a) {
  CloudsPlan p;
  std::tie(p.width, p.height) = parse_resolution("--res", a.res);
  if (a.volume_res < 8 || a.volume_res > 512) throw UsageError("--volume-res: must be in [8, 512]");
  if (a.repeat < 1 || a.repeat > 100) throw UsageError("--repeat: must be in [1, 100]");
  p.slice_counts = int_list("--slices", a.slices, 2, 4096);
  p.light_sizes = int_list("--light-res", a.light_res, 16, 4096);
  if (a.switch_slices < 2 || a.switch_slices > 4096) throw UsageError("--switch-slices: must be in [2, 4096]");
  if (a.switch_light_res < 16 || a.switch_light_res > 4096)
    throw UsageError("--switch-light-res: must be in [16, 4096]");
  for (const std::string& l : split_list(a.lights)) {
    if (l != "front" && l != "back") throw UsageError("--lights: '" + l + "' is neither front nor back");
    p.back_lit.push_back(l == "back");
  }
  if (p.back_lit.empty()) throw UsageError("--lights: empty list");
  const std::vector<std::string> steps = split_list(a.ref_steps);
  try {
    if (steps.size() != 2) throw std::invalid_argument("two numbers");
    p.ref_view = std::stod(steps[0]);
    p.ref_shadow = std::stod(steps[1]);
  } catch (const std::exception&) {
    throw UsageError("--ref-steps: expected VIEW,SHADOW in voxels, got '" + a.ref_steps + "'");
  }
  if (!(p.ref_view > 0 && p.ref_view <= 4 && p.ref_shadow > 0 && p.ref_shadow <= 4))
    throw UsageError("--ref-steps: both steps must be in (0, 4] voxels (the double-step check doubles them)");
  if (a.format != "r16f" && a.format != "r32f") throw UsageError("--format: expected r16f or r32f");
  if (!(a.sweep_half_deg > 0 && a.sweep_half_deg <= 45)) throw UsageError("--sweep-half-deg: must be in (0, 45]");
  if (!(a.sweep_step_deg > 0 && a.sweep_step_deg <= a.sweep_half_deg))
    throw UsageError("--sweep-step-deg: must be in (0, --sweep-half-deg]");
  lamp_distances(a);  // the lamps' flags before any work
  check_outputs({{"--plot", a.plot}});
  int_list("--lamp-slices", a.lamp_slices, 2, 4096);
  if (!(a.steam_voxel == 0.0 || (a.steam_voxel >= 0.001 && a.steam_voxel <= 0.05)))
    throw UsageError("--steam-voxel: must be 0 (no steam rows) or in [0.001, 0.05] metres");
  return p;
}

// The noisy sphere, as clouds and as a VDB file where vdb_render can read it (removed at the end).
struct BenchVolume {
  std::filesystem::path tmp, vdb;
  std::vector<render::CloudVolume> clouds;
  double mean_density = 0.0;
  std::size_t nonzero = 0;  // voxels > 0

  explicit BenchVolume(int volume_res)
      : tmp(std::filesystem::temp_directory_path() / ("nimbus_bench_clouds_" + std::to_string(::getpid()))) {
    const auto grid = bench_noisy_sphere(volume_res);
    std::filesystem::create_directories(tmp);
    vdb = tmp / "noisy_sphere.vdb";
    openvdb::io::File(vdb.string()).write(openvdb::GridCPtrVec{grid});
    clouds = {render::make_cloud_volume(*grid, bench_optics(1.0 / volume_res), "noisy_sphere")};
    double sum = 0.0;
    for (const float v : clouds[0].box.values) {
      sum += v;
      nonzero += v > 0.0f;
    }
    mean_density = sum / static_cast<double>(clouds[0].box.values.size());
  }
  ~BenchVolume() {
    std::error_code ec;
    std::filesystem::remove_all(tmp, ec);
  }
  BenchVolume(const BenchVolume&) = delete;
  BenchVolume& operator=(const BenchVolume&) = delete;
};

void print_header(const BenchCloudsArgs& a, const CloudsPlan& p, const BenchVolume& v, const render::Camera& camera,
                  const std::string& gl_renderer) {
  std::printf("# nimbus bench clouds: %d^3 noisy sphere (%zu voxels > 0, mean density %.3f), %dx%d, fov %.3f deg, "
              "%s\n",
              a.volume_res, v.nonzero, v.mean_density, p.width, p.height, camera.fov_deg, gl_renderer.c_str());
  std::printf("# absorb %.2f scatter %.2f per voxel, isotropic, no ambient; light irradiance 1; volume texture %s\n",
              kBenchAbsorbPerVoxel, kBenchScatterPerVoxel, a.format.c_str());
  std::printf("# error: relative RMSE of radiance over covered pixels (reference alpha > %.2f; compare_images); "
              "alpha RMSE over the same pixels\n",
              kCovered);
  std::printf("# slicer: jitter %s, no blur, no multiple scattering; GPU ms = light + slices + composite passes "
              "(CloudFrameStats), wall ms = render() with readback; best of %d\n",
              a.jitter ? "on" : "off", a.repeat);
}

// What the sun's rows measure with.
struct SunRows {
  const BenchCloudsArgs& a;
  const CloudsPlan& p;
  const BenchVolume& volume;
  const render::Camera& camera;
  render::CloudRenderer& renderer;
  std::map<std::string, PlotSeries>& series;
};

// The reference: given (--reference-dir), or rendered and timed here with its own step-doubling
// residual.
render::Image lit_reference(const SunRows& r, const Lit& lit, const std::string& name) {
  const BenchCloudsArgs& a = r.a;
  const std::filesystem::path given = a.reference_dir.empty()
                                          ? std::filesystem::path()
                                          : std::filesystem::path(a.reference_dir) / ("reference_" + name + ".exr");
  if (!given.empty() && std::filesystem::exists(given)) {
    render::Image ref = render::read_exr(given);
    if (ref.width != r.p.width || ref.height != r.p.height)
      throw UsageError("--reference-dir: " + given.string() + " has another size");
    std::printf("| reference (CPU, from %s) | %s | | | 0 | 0 | 0 |\n", given.string().c_str(),
                (ref.metadata["view_step_voxels"] + " / " + ref.metadata["shadow_step_voxels"] + " voxel").c_str());
    return ref;
  }
  const double view = r.p.ref_view, shadow = r.p.ref_shadow;
  const auto t0 = std::chrono::steady_clock::now();
  render::Image ref = reference_with_progress(r.volume.clouds, r.camera, {lit.light}, view, shadow, "reference " + name);
  const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto t1 = std::chrono::steady_clock::now();
  const render::Image coarse =
      reference_with_progress(r.volume.clouds, r.camera, {lit.light}, 2 * view, 2 * shadow, "reference x2 " + name);
  const double coarse_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  const CoveredError ce = covered_error(coarse, ref);
  std::printf("| reference (CPU, double, %u threads) | %g / %g voxel | | %.0f | 0 | 0 | 0 |\n",
              std::max(1u, std::thread::hardware_concurrency()), view, shadow, 1000.0 * ref_s);
  std::printf("| reference, steps doubled | %g / %g voxel | | %.0f | %.4f | %+.4f | %.1e |\n", 2 * view, 2 * shadow,
              1000.0 * coarse_s, ce.radiance.rel_rmse, ce.radiance.mean_bias, ce.alpha_rmse);
  save(a.out_dir, "reference_" + name, ref, true);
  return ref;
}

// The anchor: vdb_render at its default steps, -gain 0, best of --repeat runs (its own render
// time; the image is the same every run).
void vdb_render_row(const SunRows& r, const Lit& lit, const std::string& name) {
  const BenchCloudsArgs& a = r.a;
  VdbRenderRun v;
  for (int k = 0; k < a.repeat; ++k) {
    VdbRenderRun run = run_vdb_render(a.vdb_render, r.volume.vdb, r.volume.tmp / ("vdb_" + name + ".exr"), r.camera,
                                      lit.light.direction_to_sun, app::VdbRenderSettings{});
    if (k == 0 || run.render_s < v.render_s) v = std::move(run);
  }
  const render::Image img = normalise_vdb(v.image);
  const CoveredError e = covered_error(img, lit.reference);
  std::printf("| vdb_render (CPU, all cores, best of %d) | step 1 / shadowstep 3 (defaults), -gain 0 | %.0f (render) | %.0f "
              "| %.4f | %+.4f | %.1e |\n",
              a.repeat, 1000.0 * v.render_s, 1000.0 * v.wall_s, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
  PlotSeries& s = r.series["vdb_render defaults, " + name + "-lit"];
  s.name = "vdb_render defaults, " + name + "-lit";
  s.x.push_back(1000.0 * (v.render_s > 0 ? v.render_s : v.wall_s));
  s.y.push_back(std::max(e.radiance.rel_rmse, 1e-6));
  save(a.out_dir, "vdb_render_" + name, img, true);
  std::fflush(stdout);
}

// The slicer grid: every light-buffer size and slice count.
void slicer_grid_rows(const SunRows& r, const Lit& lit, const std::string& name) {
  const BenchCloudsArgs& a = r.a;
  for (const int lr : r.p.light_sizes) {
    for (const int n : r.p.slice_counts) {
      render::CloudSliceSettings s;
      s.slices = n;
      s.light_res = lr;
      s.jitter = a.jitter;
      s.ambient = false;
      s.blur_cone_rad = 0.0;
      const Timed t = timed_render(r.renderer, r.camera, lit.light, s, a.repeat);
      const CoveredError e = covered_error(t.image, lit.reference);
      std::printf("| slices (GL) | %d slices, light %d^2 | %.1f | %.1f | %.4f | %+.4f | %.1e |\n", n, lr,
                  t.best.total_ms, t.best_wall_ms, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
      std::fflush(stdout);
      const std::string key = "slices, light " + std::to_string(lr) + "^2, " + name + "-lit";
      PlotSeries& ps = r.series[key];
      ps.name = key;
      ps.x.push_back(std::max(t.best.total_ms, 1e-3));
      ps.y.push_back(std::max(e.radiance.rel_rmse, 1e-6));
      save(a.out_dir, "slices_" + name + "_" + std::to_string(n) + "_" + std::to_string(lr), t.image,
           n == a.switch_slices && lr == a.switch_light_res);
    }
  }
}

// One sun-lit case: its table of reference, anchor and slicer grid.
Lit sun_rows(const SunRows& r, bool back) {
  const std::string name = back ? "back" : "front";
  Lit lit{back, bench_light(back), {}};
  std::printf("\n## %s-lit: light towards (%.1f, %.1f, %.1f)\n\n", name.c_str(), lit.light.direction_to_sun.x,
              lit.light.direction_to_sun.y, lit.light.direction_to_sun.z);
  std::printf("| renderer | setting | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|\n");
  lit.reference = lit_reference(r, lit, name);
  std::fflush(stdout);
  if (!r.a.no_vdb_render) vdb_render_row(r, lit, name);
  slicer_grid_rows(r, lit, name);
  return lit;
}

void write_plot(const BenchCloudsArgs& a, const CloudsPlan& p, std::map<std::string, PlotSeries>& series,
                const std::string& gl_renderer) {
  Plot plot;
  plot.title = "Clouds, " + std::to_string(a.volume_res) + "^3 noisy sphere, " + std::to_string(p.width) + "x" +
               std::to_string(p.height) + ", " + gl_renderer;
  plot.x_title = "time per frame (ms): GPU passes; vdb_render: its ray-tracing time";
  plot.y_title = "relative RMSE vs CPU reference";
  for (auto& [name, s] : series) plot.series.push_back(s);
  render::write_svg_plot(a.plot, plot);
}

int run_bench_clouds(const BenchCloudsArgs& a) {
  const CloudsPlan p = check_args(a);
  if (!a.out_dir.empty()) std::filesystem::create_directories(a.out_dir);
  const BenchVolume volume(a.volume_res);
  const render::Camera camera = bench_camera(p.width, p.height);
  std::unique_ptr<render::GlContext> gl;
  try {
    gl = render::GlContext::create_headless();
  } catch (const render::GlUnavailable& e) {
    throw std::runtime_error(std::string("bench clouds needs OpenGL: ") + e.what());
  }
  // The clouds for the slicer carry an ambient sky (used only by the "ambient on" row).
  std::vector<render::CloudVolume> slicer_clouds = volume.clouds;
  slicer_clouds[0].optics.ambient_radiance = glm::dvec3(0.02, 0.025, 0.035);
  render::CloudRenderer renderer(slicer_clouds, a.format == "r32f" ? GL_R32F : GL_R16F);
  print_header(a, p, volume, camera, gl->renderer());

  std::map<std::string, PlotSeries> series;
  std::vector<Lit> lits;
  const SunRows sun{a, p, volume, camera, renderer, series};
  if (!a.no_sun)
    for (const bool back : p.back_lit) lits.push_back(sun_rows(sun, back));
  if (!a.no_lamps) bench_lamps(a, renderer, volume.clouds, camera, p.back_lit, p.ref_view, p.ref_shadow);
  if (!a.no_switches && !a.no_sun) switch_rows(a, renderer, camera, lits);
  if (!a.no_sweep && !a.no_sun) sweep_rows(a, renderer, camera);
  if (!a.plot.empty()) write_plot(a, p, series, gl->renderer());
  return 0;
}

}  // namespace

void add_bench_clouds(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchCloudsArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "clouds", "Half-angle cloud slicer: frame time against error vs the CPU reference and vdb_render");
  cmd->add_option("--res", a->res, "Image size WxH")->capture_default_str();
  cmd->add_option("--volume-res", a->volume_res, "Noisy sphere voxels per axis")->capture_default_str();
  cmd->add_option("--slices", a->slices, "Comma-separated slice counts")->capture_default_str();
  cmd->add_option("--light-res", a->light_res, "Comma-separated light-buffer sizes")->capture_default_str();
  cmd->add_option("--lights", a->lights, "front, back or both")->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "Timed frames per setting (best is reported)")->capture_default_str();
  cmd->add_option("--ref-steps", a->ref_steps, "Reference view,shadow steps in voxels")->capture_default_str();
  cmd->add_flag("--jitter", a->jitter, "Jittered slice offsets in the slicer grid and the sweep");
  cmd->add_option("--format", a->format, "Volume texture: r16f or r32f")->capture_default_str();
  cmd->add_option("--vdb-render", a->vdb_render, "The vdb_render binary")->capture_default_str();
  cmd->add_flag("--no-vdb-render", a->no_vdb_render, "Skip the vdb_render anchor");
  cmd->add_flag("--no-switches", a->no_switches, "Skip the blur/ambient/multiple-scattering/jitter rows");
  cmd->add_flag("--no-sweep", a->no_sweep, "Skip the popping sweep");
  cmd->add_flag("--no-sun", a->no_sun, "Skip the sun's rows (grid, switches, sweep)");
  cmd->add_flag("--no-lamps", a->no_lamps, "Skip the lamps' rows");
  cmd->add_option("--lamp-distances", a->lamp_distances, "Lamp distances from the sphere's centre, metres (the first "
                  "gets the slice sweep and the two-lamp rows)")->capture_default_str();
  cmd->add_option("--lamp-slices", a->lamp_slices, "Slice counts of the lamp and steam rows")->capture_default_str();
  cmd->add_option("--steam-voxel", a->steam_voxel, "Voxel of the steam-under-a-lamp rows, metres (0: skip them)")
      ->capture_default_str();
  cmd->add_option("--switch-slices", a->switch_slices, "Slices for the switch rows and the sweep")
      ->capture_default_str();
  cmd->add_option("--switch-light-res", a->switch_light_res, "Light buffer for the switch rows and the sweep")
      ->capture_default_str();
  cmd->add_option("--sweep-half-deg", a->sweep_half_deg, "Sweep from 90 - H to 90 + H degrees")->capture_default_str();
  cmd->add_option("--sweep-step-deg", a->sweep_step_deg, "Sweep step, degrees")->capture_default_str();
  cmd->add_option("--reference-dir", a->reference_dir, "Read reference_front.exr / reference_back.exr from here");
  cmd->add_option("--out-dir", a->out_dir, "Write the reference, vdb_render and slicer images here");
  cmd->add_option("--plot", a->plot, "Write an SVG plot of time against error here");
  cmd->callback([&action, a] { action = [a] { return run_bench_clouds(*a); }; });
}

}  // namespace nimbus::cli
