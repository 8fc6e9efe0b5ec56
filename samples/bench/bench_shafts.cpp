// `nimbus bench shafts`: speed against error of the light-shaft methods. Every GPU method and
// setting renders the same scene and camera; its frame time is set beside its image error
// against the exact CPU reference (relative RMSE and maximum over lit pixels), and the
// reference's own time is the anchor measured in the same run. Scenes with point lights also get
// the surface airlight's rows (Sun et al. eq. 13's L_p,a): frame time with and without it, its
// image error against the reference (which adds the same term), and its CPU cost per evaluation.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <map>
#include <cstdio>
#include <mutex>
#include <sstream>

#include "cli/cli.hpp"
#include "cli/outputs.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/media/surface_airlight.hpp"
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

void bench_surface_airlight_cpu();
void bench_surface_airlight_gpu(const render::Scene& scene, const render::Camera& camera, const render::Image& reference,
                                const render::ShaftSettings& base, int repeat);

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
    for (render::Light& l : scene.lamps) l.bulb_radius_m = 0.0;
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
  check_outputs({{"--plot", a.plot}});

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
  if (!scene.lamps.empty()) {
    bench_surface_airlight_gpu(scene, camera, reference, settings, a.repeat);
    bench_surface_airlight_cpu();
  }
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

// ns per evaluation of each surface-airlight evaluation on the CPU (one core), over queries drawn
// with a fixed seed (Tsp log-uniform in [1e-4, 50], theta_s uniform in [0, pi]), and the float
// path's largest relative error against the reference over them.
void bench_surface_airlight_cpu() {
  const render::SurfaceAirlightTable table;  // isotropic (already built by the GPU rows)
  // A table's build time: one for a phase function not built before in this run.
  const auto t_table = std::chrono::steady_clock::now();
  const render::SurfaceAirlightTable fresh(render::Phase{render::PhaseKind::HenyeyGreenstein, 0.123456789});
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_table).count();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<render::SurfaceAirlightQuery> queries(1 << 16);
  for (auto& q : queries) {
    q.Dsp = 1.0;
    q.sigma_t = 1e-4 * std::pow(5e5, unit(rng));
    q.sigma_s = q.sigma_t;
    q.cos_theta_s = std::cos(M_PI * unit(rng));
  }
  auto time_ns = [&](std::size_t n, auto&& f) {
    double sink = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < n; ++i) sink += f(queries[i]);
    const double ns = 1e9 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / double(n);
    if (!(sink >= 0.0)) std::printf("# (unexpected sum %g)\n", sink);
    return ns;
  };
  const std::size_t n_ref = 64;
  std::vector<double> ref(n_ref);
  const double ref_ns = time_ns(n_ref, [&](const render::SurfaceAirlightQuery& q) {
    const std::size_t i = std::size_t(&q - queries.data());
    return ref[i] = render::surface_airlight_reference(q);
  });
  double worst_float = 0.0, worst_double = 0.0;
  for (std::size_t i = 0; i < n_ref; ++i) {
    worst_float = std::max(worst_float, std::abs(render::surface_airlight_float(queries[i], table) / ref[i] - 1.0));
    worst_double = std::max(worst_double, std::abs(render::surface_airlight_table(queries[i], table) / ref[i] - 1.0));
  }
  const double float_ns = time_ns(queries.size(), [&](const render::SurfaceAirlightQuery& q) {
    return render::surface_airlight_float(q, table);
  });
  const double double_ns = time_ns(queries.size(), [&](const render::SurfaceAirlightQuery& q) {
    return render::surface_airlight_table(q, table);
  });
  std::printf("\n# surface airlight, CPU, one core: ns per evaluation (Tsp log-uniform in [1e-4, 50], theta_s uniform; "
              "tables %dx%d, one builds in %.2f s)\n",
              table.nx(), table.ny(), build_s);
  std::printf("| evaluation | ns per evaluation | max rel. error vs reference (%zu queries) |\n|---|---:|---:|\n", n_ref);
  std::printf("| reference (nested Gauss-Kronrod, double) | %.3g | (reference) |\n", ref_ns);
  std::printf("| table, double (scene reference) | %.3g | %.2e |\n", double_ns, worst_double);
  std::printf("| table, float (the shader's source as C++) | %.3g | %.2e |\n", float_ns, worst_float);
}

// Frame time with and without the surface airlight (GPU, analytic:stable shafts, best of
// `repeat`), and each image's error against the reference, which adds the term.
void bench_surface_airlight_gpu(const render::Scene& scene, const render::Camera& camera, const render::Image& reference,
                                const render::ShaftSettings& base, int repeat) {
  std::printf("\n# surface airlight (Sun et al. eq. 13, L_p,a), shafts analytic:stable; the reference adds the term\n");
  std::printf("| surface airlight | surfaces ms | frame ms | rel. RMSE | median rel. | max rel. | bias |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  const render::ShaftMethod method = render::parse_shaft_method("analytic:stable");
  for (bool on : {false, true}) {
    render::ShaftSettings settings = base;
    settings.surface_airlight = on;
    render::ShaftRenderer renderer(scene, settings);
    render::ShaftFrameStats st, best;
    render::Image img = renderer.render(camera, method, &st);  // warm-up: compiles
    best.total_ms = 1e300;
    for (int r = 0; r < repeat; ++r) {
      img = renderer.render(camera, method, &st);
      const double frame = st.surfaces_ms + st.shadow_volume_ms + st.shafts_ms;
      if (frame < best.total_ms) {
        best = st;
        best.total_ms = frame;
      }
    }
    const render::ImageError err = render::compare_images(img, reference);
    std::printf("| %s | %.1f | %.1f | %.4f | %.1e | %.3f | %+.4f |\n", on ? "on" : "off", best.surfaces_ms,
                best.total_ms, err.rel_rmse, err.median_rel, err.max_rel, err.mean_bias);
    std::fflush(stdout);
  }
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
