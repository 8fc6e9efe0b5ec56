// `nimbus bench shafts`: speed against error of the light-shaft methods. Every GPU method and
// setting renders the same scene and camera; its frame time is set beside its image error
// against the exact CPU reference (relative RMSE and maximum over lit pixels), and the
// reference's own time is the anchor measured in the same run.
#include <algorithm>
#include <chrono>
#include <map>
#include <cstdio>
#include <mutex>
#include <sstream>

#include "cli/cli.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"
#include "nimbus/render/core/scene.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"
#include "cli/progress.hpp"
#include "cli/render_args.hpp"
#include "nimbus/render/image/svg_plot.hpp"

namespace nimbus::cli {
namespace {

using render::Plot;
using render::PlotSeries;
using render::write_svg_plot;

struct BenchShaftsArgs {
  std::string scene = "lamps";
  CameraArgs camera;
  std::string methods =
      "raymarch:5,raymarch:20,raymarch:100,raymarch:200,raymarch:500,raymarch:1000,raymarch:4000,"
      "analytic:table:16,analytic:table:32,analytic:table:64,analytic:table:128,analytic:table:256,analytic:stable,"
      "shadowvolume:5,shadowvolume:20,shadowvolume:100,shadowvolume:200";
  int repeat = 3;
  int shadow_res = 1024;
  std::string reference_in, reference_out, plot;
  bool bulbs = false;
};


int run_bench_shafts(const BenchShaftsArgs& a) {
  render::Scene scene;
  try {
    scene = render::make_scene(a.scene);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--scene: ") + e.what());
  }
  // A light seen directly is the same in every method and its few pixels would outweigh the
  // fog in the error: bulbs are hidden unless asked for.
  if (!a.bulbs)
    for (render::PointLight& l : scene.point_lights) l.bulb_radius_m = 0.0;
  render::Camera camera = scene.camera;
  camera.width = 1280;
  camera.height = 720;
  camera = apply_camera_args(a.camera, camera);
  if (a.repeat < 1 || a.repeat > 100) throw UsageError("--repeat: must be in [1, 100]");
  std::vector<render::ShaftMethod> methods;
  for (const std::string& m : split_list(a.methods)) {
    try {
      methods.push_back(render::parse_shaft_method(m));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--methods: ") + e.what());
    }
    if (methods.back().kind == render::ShaftMethod::Kind::Reference)
      throw UsageError("--methods: the reference is always measured; list GPU methods only");
  }

  // The anchor: the exact CPU reference, rendered (and timed) in this run unless given.
  render::Image reference;
  double reference_s = 0.0;
  if (!a.reference_in.empty()) {
    reference = render::read_exr(a.reference_in);
    if (reference.width != camera.width || reference.height != camera.height)
      throw UsageError("--reference: " + a.reference_in + " is " + std::to_string(reference.width) + "x" +
                       std::to_string(reference.height) + ", the bench renders " + std::to_string(camera.width) +
                       "x" + std::to_string(camera.height));
  } else {
    const auto t0 = std::chrono::steady_clock::now();
    reference = render_reference_with_progress(scene, camera);
    reference_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!a.reference_out.empty()) render::write_exr(a.reference_out, reference);
  }

  std::unique_ptr<render::GlContext> gl;
  try {
    gl = render::GlContext::create_headless();
  } catch (const render::GlUnavailable& e) {
    throw std::runtime_error(std::string("bench shafts needs OpenGL: ") + e.what());
  }
  render::ShaftSettings settings;
  settings.point_shadow_res = a.shadow_res;
  settings.sun_shadow_res = 2 * a.shadow_res;
  render::ShaftRenderer renderer(scene, settings);

  std::printf("# nimbus bench shafts: scene %s, %dx%d, %s, shadow maps %d^2 per cube face\n", scene.name.c_str(),
              camera.width, camera.height, gl->renderer().c_str(), a.shadow_res);
  std::printf("# bulbs %s; error over the reference's lit pixels (nimbus::render::compare_images)\n",
              a.bulbs ? "visible" : "hidden");
  std::printf("# frame = surfaces + shadow volume + shafts (GPU time, best of %d); shadow maps are built once per scene\n",
              a.repeat);
  std::printf("| method | frame ms | shafts ms | rel. RMSE | median rel. | max rel. | bias | skirts |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  if (reference_s > 0)
    std::printf("| reference (CPU, double, TBB) | %.0f | | 0 | 0 | 0 | 0 | |\n", 1000.0 * reference_s);
  std::map<std::string, PlotSeries> series;
  double shadow_ms = 0.0;
  for (const render::ShaftMethod& m : methods) {
    if (m.kind == render::ShaftMethod::Kind::Analytic && m.airlight.kind == render::AirlightMethod::Table &&
        scene.medium.phase.kind != render::PhaseKind::Isotropic) {
      std::printf("| %s | n/a: Sun's table covers the isotropic phase only (scene: %s) | | | | | | |\n",
                  render::to_string(m).c_str(), render::to_string(scene.medium.phase).c_str());
      continue;
    }
    render::ShaftFrameStats st, best;
    render::Image img = renderer.render(camera, m, &st);  // warm-up: compiles the program
    shadow_ms = std::max(shadow_ms, st.shadow_maps_ms);
    best.total_ms = 1e300;
    for (int r = 0; r < a.repeat; ++r) {
      img = renderer.render(camera, m, &st);
      const double frame = st.surfaces_ms + st.shadow_volume_ms + st.shafts_ms;
      if (frame < best.total_ms) {
        best = st;
        best.total_ms = frame;
      }
    }
    const render::ImageError err = render::compare_images(img, reference);
    std::printf("| %s | %.1f | %.1f | %.4f | %.1e | %.3f | %+.4f | %s |\n", render::to_string(m).c_str(), best.total_ms,
                best.shafts_ms, err.rel_rmse, err.median_rel, err.max_rel, err.mean_bias,
                m.kind == render::ShaftMethod::Kind::ShadowVolume ? std::to_string(best.skirt_quads).c_str() : "");
    std::fflush(stdout);
    std::string family = render::to_string(m);
    family = family.substr(0, family.rfind(':'));
    if (m.kind == render::ShaftMethod::Kind::Analytic) family = "analytic (table N; stable)";
    PlotSeries& s = series[family];
    s.name = family;
    s.x.push_back(best.total_ms);
    s.y.push_back(std::max(err.rel_rmse, 1e-6));
  }
  std::printf("# shadow maps: %.1f ms (once); lit pixels compared: %zu\n", shadow_ms,
              render::compare_images(reference, reference).pixels);
  if (!a.plot.empty()) {
    Plot p;
    p.title = "Light shafts, scene " + scene.name + ", " + std::to_string(camera.width) + "x" +
              std::to_string(camera.height) + ", " + gl->renderer();
    p.x_title = "GPU time per frame (ms)";
    p.y_title = "relative RMSE vs CPU reference";
    for (auto& [name, s] : series) p.series.push_back(s);
    write_svg_plot(a.plot, p);
  }
  return 0;
}

}  // namespace

void add_bench_shafts(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchShaftsArgs>();
  CLI::App* cmd = bench.add_subcommand("shafts", "Light-shaft methods: frame time against error vs the CPU reference");
  cmd->add_option("--scene", a->scene, "Scene to render")->capture_default_str();
  add_camera_options(cmd, a->camera);
  cmd->add_option("--methods", a->methods, "Comma-separated GPU methods")->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "Timed frames per method (best is reported)")->capture_default_str();
  cmd->add_option("--shadow-res", a->shadow_res, "Point-light shadow map size per cube face")->capture_default_str();
  cmd->add_option("--reference", a->reference_in, "Use this reference EXR instead of rendering it");
  cmd->add_option("--save-reference", a->reference_out, "Write the reference rendered in this run here");
  cmd->add_option("--plot", a->plot, "Write an SVG plot of time against error here");
  cmd->add_flag("--bulbs", a->bulbs, "Keep the lights' visible bulbs (hidden by default)");
  cmd->callback([&action, a] { action = [a] { return run_bench_shafts(*a); }; });
}

}  // namespace nimbus::cli
