// `nimbus bench clouds`: speed against error of the half-angle slice renderer on the noisy sphere
// of research-render.md section 5. Every slice count and light-buffer size renders the same
// volume, camera and light (front-lit and back-lit); its frame time is set beside its error
// against the CPU single-scattering reference, with OpenVDB's vdb_render (defaults, -gain 0) on
// the same VDB as the anchor measured in the same run; then the optional terms one at a time
// (blur, ambient, multiple scattering, jitter), the popping sweep through the branch switch, and
// the same for lamps (point lights near and far, two at once) and the steam under a lamp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>

#include <unistd.h>

#include "nimbus/app/bench_clouds_scene.hpp"
#include "cli/cli.hpp"
#include "cli/outputs.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/core/scene.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"
#include "cli/progress.hpp"
#include "cli/render_args.hpp"
#include "nimbus/render/image/svg_plot.hpp"

namespace nimbus::cli {

using app::bench_camera;
using app::kBenchAbsorbPerVoxel;
using app::kBenchScatterPerVoxel;
using app::bench_light;
using app::bench_noisy_sphere;
using app::bench_optics;
using app::run_vdb_render;
using app::VdbRenderRun;
namespace {

using render::Plot;
using render::PlotSeries;
using render::write_svg_plot;

constexpr double kPi = 3.14159265358979323846;
constexpr double kCovered = 0.01;  // a pixel counts where the reference's alpha exceeds this

struct BenchCloudsArgs {
  std::string res = "512x512";
  int volume_res = 128;
  std::string slices = "32,64,128,256,512";
  std::string light_res = "128,256,512,1024";
  std::string lights = "front,back";
  int repeat = 3;
  std::string ref_steps = "0.25,0.5";
  bool jitter = false;
  std::string format = "r16f";
  std::string vdb_render = "/usr/bin/vdb_render";
  bool no_vdb_render = false, no_switches = false, no_sweep = false, no_sun = false, no_lamps = false;
  std::string lamp_distances = "4,1.5,0.75";  // metres from the sphere's centre (its radius is 0.47)
  std::string lamp_slices = "64,128,256";
  double steam_voxel = 0.003;                 // the steam-under-a-lamp row's voxel, metres (0: skip the row)
  int switch_slices = 128, switch_light_res = 256;
  double sweep_half_deg = 10.0, sweep_step_deg = 0.5;
  std::string plot, out_dir, reference_dir;
};

std::vector<int> int_list(const std::string& flag, const std::string& text, int lo, int hi) {
  std::vector<int> out;
  for (const std::string& s : split_list(text)) {
    const std::optional<int> v = parse_int_in(s, lo, hi);
    if (!v)
      throw UsageError(flag + ": '" + s + "' is not an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                       "]");
    out.push_back(*v);
  }
  if (out.empty()) throw UsageError(flag + ": empty list");
  return out;
}

// Error of `test` against `reference` over the covered pixels (reference alpha > kCovered):
// compare_images on the radiance with the uncovered pixels of the reference blacked out, and
// the RMSE of alpha.
struct CoveredError {
  render::ImageError radiance;
  double alpha_rmse = 0.0;
};
CoveredError covered_error(const render::Image& test, const render::Image& reference) {
  render::Image masked = reference;
  double sum_sq = 0.0;
  std::size_t n = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      float* r = masked.pixel(x, y);
      if (r[3] > kCovered) {
        const double d = test.pixel(x, y)[3] - r[3];
        sum_sq += d * d;
        ++n;
      } else {
        r[0] = r[1] = r[2] = 0.0f;
      }
    }
  CoveredError e;
  e.radiance = render::compare_images(test, masked);
  e.alpha_rmse = n ? std::sqrt(sum_sq / n) : 0.0;
  return e;
}

// vdb_render's radiance carries an unnormalised phase (weight 1): ours is it / 4 pi.
render::Image normalise_vdb(render::Image img) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = static_cast<float>(img.pixel(x, y)[c] / (4.0 * kPi));
  return img;
}

void save(const std::string& dir, const std::string& name, const render::Image& img, bool preview) {
  if (dir.empty()) return;
  render::write_exr(std::filesystem::path(dir) / (name + ".exr"), img);
  if (!preview) return;
  render::PreviewOptions o;
  o.exposure_stops = render::auto_exposure_stops(img);
  render::write_png_preview(std::filesystem::path(dir) / (name + ".png"), img, o);
}

struct Timed {
  render::Image image;
  render::CloudFrameStats best;  // best GPU total of the repeats
  double best_wall_ms = 1e300;
};

Timed timed_render(render::CloudRenderer& r, const render::Camera& cam, const std::vector<render::CloudLight>& lights,
                   const render::CloudSliceSettings& s, int repeat) {
  Timed t;
  render::CloudFrameStats st;
  t.image = r.render(cam, lights, s, nullptr, &st);  // warm-up: programs, buffers
  t.best.total_ms = 1e300;
  for (int i = 0; i < repeat; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    t.image = r.render(cam, lights, s, nullptr, &st);
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    t.best_wall_ms = std::min(t.best_wall_ms, wall);
    if (st.total_ms < t.best.total_ms) t.best = st;
  }
  return t;
}

Timed timed_render(render::CloudRenderer& r, const render::Camera& cam, const render::CloudLight& light,
                   const render::CloudSliceSettings& s, int repeat) {
  return timed_render(r, cam, std::vector<render::CloudLight>{light}, s, repeat);
}

render::Image reference_with_progress(const std::vector<render::CloudVolume>& clouds, const render::Camera& cam,
                                      const std::vector<render::CloudLight>& light, double view_step,
                                      double shadow_step, const std::string& what) {
  Progress progress(what);
  render::CloudReferenceSettings s;
  s.view_step_voxels = view_step;
  s.shadow_step_voxels = shadow_step;
  s.progress = [&](double f) { progress.update(f); };
  return render::render_cloud_reference(clouds, cam, light, s);
}

// The lamps: the noisy sphere lit by a lamp at a distance along the sun's front- and back-lit
// directions (intensity d^2, so about 1 W m^-2 at the centre), slicer against the CPU reference;
// two lamps at once against one pass each dropped; and the steam of the `steam-lamp` scene.
// --lamp-distances as metres; a usage error naming the flag.
std::vector<double> lamp_distances(const BenchCloudsArgs& a) {
  std::vector<double> distances;
  for (const std::string& t : split_list(a.lamp_distances)) {
    const std::optional<double> d = parse_double(t);
    if (!d || !(*d > 0.5 && *d <= 1000.0)) throw UsageError("--lamp-distances: '" + t + "' must be in (0.5, 1000] metres");
    distances.push_back(*d);
  }
  if (distances.empty()) throw UsageError("--lamp-distances: empty list");
  return distances;
}

// The lamp and steam rows' slicer settings: n slices, the switch rows' light buffer, no ambient.
render::CloudSliceSettings lamp_row_settings(const BenchCloudsArgs& a, int n) {
  render::CloudSliceSettings s;
  s.slices = n;
  s.light_res = a.switch_light_res;
  s.jitter = a.jitter;
  s.ambient = false;
  return s;
}

void bench_lamps(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const std::vector<render::CloudVolume>& clouds,
                 const render::Camera& camera, const std::vector<bool>& back_lit, double ref_view, double ref_shadow) {
  const std::vector<double> distances = lamp_distances(a);
  const std::vector<int> slice_counts = int_list("--lamp-slices", a.lamp_slices, 2, 4096);
  auto lamp = [](bool back, double d) {
    const glm::dvec3 dir = glm::normalize(bench_light(back).direction_to_light);
    return render::point_light(d * dir, glm::dvec3(d * d));
  };
  std::printf("\n## Lamps: a point light at distance d from the sphere's centre (radius 0.47) along the front- or "
              "back-lit direction, intensity d^2 W/sr\n\n");
  std::printf("| lighting | d (m) | slices, light | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|\n");
  std::map<bool, render::Image> mid_reference;  // at the first distance, for the two-lamp rows
  for (const bool back : back_lit) {
    for (std::size_t di = 0; di < distances.size(); ++di) {
      const double d = distances[di];
      const std::vector<render::CloudLight> lights = {lamp(back, d)};
      const auto t0 = std::chrono::steady_clock::now();
      const render::Image ref = reference_with_progress(clouds, camera, lights, ref_view, ref_shadow,
                                                        std::string("reference lamp ") + (back ? "back" : "front"));
      const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("| %s-lit | %.2f | reference (CPU, double), %g / %g voxel | | %.0f | 0 | 0 | 0 |\n", back ? "back" : "front",
                  d, ref_view, ref_shadow, 1000.0 * ref_s);
      if (di == 0) mid_reference[back] = ref;
      for (const int n : slice_counts) {
        if (di > 0 && n != a.switch_slices) continue;  // the slice sweep at the first distance only
        const render::CloudSliceSettings s = lamp_row_settings(a, n);
        const Timed t = timed_render(renderer, camera, lights, s, a.repeat);
        const CoveredError e = covered_error(t.image, ref);
        std::printf("| %s-lit | %.2f | %d slices, light %d^2 | %.1f | %.1f | %.4f | %+.4f | %.1e |\n",
                    back ? "back" : "front", d, n, a.switch_light_res, t.best.total_ms, t.best_wall_ms,
                    e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
        std::fflush(stdout);
        save(a.out_dir, std::string("lamp_") + (back ? "back" : "front") + "_" + std::to_string(n), t.image,
             n == a.switch_slices && di == 0);
      }
      save(a.out_dir, std::string("lamp_reference_") + (back ? "back" : "front") + "_" + std::to_string(di), ref, di == 0);
    }
  }
  // Two lamps: one pass each, against the sum of their references; with max_lights 1 the weaker
  // one is left out, and its share is the error.
  if (mid_reference.size() == 2) {
    const double d = distances.front();
    const std::vector<render::CloudLight> both = {lamp(false, d), lamp(true, d)};
    render::Image sum = mid_reference[false];
    for (int y = 0; y < sum.height; ++y)
      for (int x = 0; x < sum.width; ++x)
        for (int c = 0; c < 3; ++c) sum.pixel(x, y)[c] += mid_reference[true].pixel(x, y)[c];
    std::printf("\n| two lamps (front and back, d %.2f) | passes | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n", d);
    std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
    for (const int max_lights : {2, 1}) {
      render::CloudSliceSettings s = lamp_row_settings(a, a.switch_slices);
      s.max_lights = max_lights;
      const Timed t = timed_render(renderer, camera, both, s, a.repeat);
      const CoveredError e = covered_error(t.image, sum);
      std::printf("| max_lights %d | %d | %.1f | %.1f | %.4f | %+.4f | %.1e |\n", max_lights, t.best.light_passes,
                  t.best.total_ms, t.best_wall_ms, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
      std::fflush(stdout);
    }
  }
  // The steam of the seed's teacup under the street lamp (scene steam-lamp), clouds alone.
  if (a.steam_voxel > 0.0) {
    const render::Scene scene = render::make_scene("steam-lamp");
    render::CloudOptics optics;
    optics.extinction_per_m = *scene.cloud_extinction_per_m;
    optics.phase = render::parse_cloud_phase("dual:0.7,-0.25,0.8");
    const std::vector<render::CloudVolume> steam = {
        render::generate_preset_cloud(render::load_preset_cloud("steam"), a.steam_voxel, 0.0, optics)};
    render::Camera cam = scene.camera;
    cam.width = camera.width;
    cam.height = camera.height;
    const std::vector<render::CloudLight> lights = {
        render::point_light(scene.point_lights[0].position_m, scene.point_lights[0].intensity_w_sr)};
    const auto t0 = std::chrono::steady_clock::now();
    const render::Image ref = reference_with_progress(steam, cam, lights, ref_view, ref_shadow, "reference steam");
    const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    render::CloudRenderer steam_renderer(steam, a.format == "r32f" ? GL_R32F : GL_R16F);
    std::printf("\n## Steam under the lamp (scene steam-lamp, preset steam at %g m voxels: %dx%dx%d, extinction %g per "
                "metre, dual-lobe phase 0.7/-0.25/0.8), clouds alone\n\n",
                a.steam_voxel, static_cast<int>(steam[0].box.size[0]), static_cast<int>(steam[0].box.size[1]),
                static_cast<int>(steam[0].box.size[2]), optics.extinction_per_m);
    std::printf("| renderer | setting | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|\n");
    std::printf("| reference (CPU, double) | %g / %g voxel | | %.0f | 0 | 0 | 0 |\n", ref_view, ref_shadow, 1000.0 * ref_s);
    for (const int n : slice_counts) {
      const render::CloudSliceSettings s = lamp_row_settings(a, n);
      const Timed t = timed_render(steam_renderer, cam, lights, s, a.repeat);
      const CoveredError e = covered_error(t.image, ref);
      std::printf("| slices (GL) | %d slices, light %d^2 | %.1f | %.1f | %.4f | %+.4f | %.1e |\n", n, a.switch_light_res,
                  t.best.total_ms, t.best_wall_ms, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
      std::fflush(stdout);
      save(a.out_dir, "steam_" + std::to_string(n), t.image, n == a.switch_slices);
    }
    save(a.out_dir, "steam_reference", ref, true);
  }
}

int run_bench_clouds(const BenchCloudsArgs& a) {
  const auto [width, height] = parse_resolution("--res", a.res);
  if (a.volume_res < 8 || a.volume_res > 512) throw UsageError("--volume-res: must be in [8, 512]");
  if (a.repeat < 1 || a.repeat > 100) throw UsageError("--repeat: must be in [1, 100]");
  const std::vector<int> slice_counts = int_list("--slices", a.slices, 2, 4096);
  const std::vector<int> light_sizes = int_list("--light-res", a.light_res, 16, 4096);
  if (a.switch_slices < 2 || a.switch_slices > 4096) throw UsageError("--switch-slices: must be in [2, 4096]");
  if (a.switch_light_res < 16 || a.switch_light_res > 4096)
    throw UsageError("--switch-light-res: must be in [16, 4096]");
  std::vector<bool> back_lit;
  for (const std::string& l : split_list(a.lights)) {
    if (l != "front" && l != "back") throw UsageError("--lights: '" + l + "' is neither front nor back");
    back_lit.push_back(l == "back");
  }
  if (back_lit.empty()) throw UsageError("--lights: empty list");
  const std::vector<std::string> steps = split_list(a.ref_steps);
  double ref_view = 0, ref_shadow = 0;
  try {
    if (steps.size() != 2) throw std::invalid_argument("two numbers");
    ref_view = std::stod(steps[0]);
    ref_shadow = std::stod(steps[1]);
  } catch (const std::exception&) {
    throw UsageError("--ref-steps: expected VIEW,SHADOW in voxels, got '" + a.ref_steps + "'");
  }
  if (!(ref_view > 0 && ref_view <= 4 && ref_shadow > 0 && ref_shadow <= 4))
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
  if (!a.out_dir.empty()) std::filesystem::create_directories(a.out_dir);

  // The volume, written where vdb_render can read it.
  const auto grid = bench_noisy_sphere(a.volume_res);
  const double voxel = 1.0 / a.volume_res;
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() / ("nimbus_bench_clouds_" + std::to_string(::getpid()));
  std::filesystem::create_directories(tmp);
  struct Cleanup {
    std::filesystem::path p;
    ~Cleanup() {
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
    }
  } cleanup{tmp};
  const std::filesystem::path vdb = tmp / "noisy_sphere.vdb";
  openvdb::io::File(vdb.string()).write(openvdb::GridCPtrVec{grid});
  const std::vector<render::CloudVolume> clouds = {
      render::make_cloud_volume(*grid, bench_optics(voxel), "noisy_sphere")};
  double sum = 0.0;
  std::size_t nonzero = 0;
  for (const float v : clouds[0].box.values) {
    sum += v;
    nonzero += v > 0.0f;
  }
  const render::Camera camera = bench_camera(width, height);

  std::unique_ptr<render::GlContext> gl;
  try {
    gl = render::GlContext::create_headless();
  } catch (const render::GlUnavailable& e) {
    throw std::runtime_error(std::string("bench clouds needs OpenGL: ") + e.what());
  }
  // The clouds for the slicer carry an ambient sky (used only by the "ambient on" row).
  std::vector<render::CloudVolume> slicer_clouds = clouds;
  slicer_clouds[0].optics.ambient_radiance = glm::dvec3(0.02, 0.025, 0.035);
  render::CloudRenderer renderer(slicer_clouds, a.format == "r32f" ? GL_R32F : GL_R16F);

  std::printf("# nimbus bench clouds: %d^3 noisy sphere (%zu voxels > 0, mean density %.3f), %dx%d, fov %.3f deg, "
              "%s\n",
              a.volume_res, nonzero, sum / static_cast<double>(clouds[0].box.values.size()), width, height,
              camera.fov_deg, gl->renderer().c_str());
  std::printf("# absorb %.2f scatter %.2f per voxel, isotropic, no ambient; light irradiance 1; volume texture %s\n",
              kBenchAbsorbPerVoxel, kBenchScatterPerVoxel, a.format.c_str());
  std::printf("# error: relative RMSE of radiance over covered pixels (reference alpha > %.2f; compare_images); "
              "alpha RMSE over the same pixels\n",
              kCovered);
  std::printf("# slicer: jitter %s, no blur, no multiple scattering; GPU ms = light + slices + composite passes "
              "(CloudFrameStats), wall ms = render() with readback; best of %d\n",
              a.jitter ? "on" : "off", a.repeat);

  std::map<std::string, PlotSeries> series;
  struct Lit {
    bool back;
    render::CloudLight light;
    render::Image reference;
  };
  std::vector<Lit> lits;
  for (const bool back : back_lit) {
    if (a.no_sun) break;
    const std::string name = back ? "back" : "front";
    Lit lit{back, bench_light(back), {}};
    std::printf("\n## %s-lit: light towards (%.1f, %.1f, %.1f)\n\n", name.c_str(), lit.light.direction_to_light.x,
                lit.light.direction_to_light.y, lit.light.direction_to_light.z);
    std::printf("| renderer | setting | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|\n");
    // The reference: given, or rendered and timed here, with its own step-doubling residual.
    const std::filesystem::path given = a.reference_dir.empty()
                                            ? std::filesystem::path()
                                            : std::filesystem::path(a.reference_dir) / ("reference_" + name + ".exr");
    if (!given.empty() && std::filesystem::exists(given)) {
      lit.reference = render::read_exr(given);
      if (lit.reference.width != width || lit.reference.height != height)
        throw UsageError("--reference-dir: " + given.string() + " has another size");
      std::printf("| reference (CPU, from %s) | %s | | | 0 | 0 | 0 |\n", given.string().c_str(),
                  (lit.reference.metadata["view_step_voxels"] + " / " + lit.reference.metadata["shadow_step_voxels"] +
                   " voxel")
                      .c_str());
    } else {
      const auto t0 = std::chrono::steady_clock::now();
      lit.reference = reference_with_progress(clouds, camera, {lit.light}, ref_view, ref_shadow, "reference " + name);
      const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const auto t1 = std::chrono::steady_clock::now();
      const render::Image coarse =
          reference_with_progress(clouds, camera, {lit.light}, 2 * ref_view, 2 * ref_shadow, "reference x2 " + name);
      const double coarse_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      const CoveredError ce = covered_error(coarse, lit.reference);
      std::printf("| reference (CPU, double, %u threads) | %g / %g voxel | | %.0f | 0 | 0 | 0 |\n",
                  std::max(1u, std::thread::hardware_concurrency()), ref_view, ref_shadow, 1000.0 * ref_s);
      std::printf("| reference, steps doubled | %g / %g voxel | | %.0f | %.4f | %+.4f | %.1e |\n", 2 * ref_view,
                  2 * ref_shadow, 1000.0 * coarse_s, ce.radiance.rel_rmse, ce.radiance.mean_bias, ce.alpha_rmse);
      save(a.out_dir, "reference_" + name, lit.reference, true);
    }
    std::fflush(stdout);
    // The anchor: vdb_render at its default steps, -gain 0.
    if (!a.no_vdb_render) {
      VdbRenderRun v;  // best of --repeat runs (its own render time; the image is the same every run)
      for (int r = 0; r < a.repeat; ++r) {
        VdbRenderRun run = run_vdb_render(a.vdb_render, vdb, tmp / ("vdb_" + name + ".exr"), camera, lit.light.direction_to_light, app::VdbRenderSettings{});
        if (r == 0 || run.render_s < v.render_s) v = std::move(run);
      }
      const render::Image img = normalise_vdb(v.image);
      const CoveredError e = covered_error(img, lit.reference);
      std::printf("| vdb_render (CPU, all cores, best of %d) | step 1 / shadowstep 3 (defaults), -gain 0 | %.0f (render) | %.0f "
                  "| %.4f | %+.4f | %.1e |\n",
                  a.repeat, 1000.0 * v.render_s, 1000.0 * v.wall_s, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
      PlotSeries& s = series["vdb_render defaults, " + name + "-lit"];
      s.name = "vdb_render defaults, " + name + "-lit";
      s.x.push_back(1000.0 * (v.render_s > 0 ? v.render_s : v.wall_s));
      s.y.push_back(std::max(e.radiance.rel_rmse, 1e-6));
      save(a.out_dir, "vdb_render_" + name, img, true);
      std::fflush(stdout);
    }
    // The slicer grid.
    for (const int lr : light_sizes) {
      for (const int n : slice_counts) {
        render::CloudSliceSettings s;
        s.slices = n;
        s.light_res = lr;
        s.jitter = a.jitter;
        s.ambient = false;
        s.blur_cone_rad = 0.0;
        const Timed t = timed_render(renderer, camera, lit.light, s, a.repeat);
        const CoveredError e = covered_error(t.image, lit.reference);
        std::printf("| slices (GL) | %d slices, light %d^2 | %.1f | %.1f | %.4f | %+.4f | %.1e |\n", n, lr,
                    t.best.total_ms, t.best_wall_ms, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
        std::fflush(stdout);
        const std::string key = "slices, light " + std::to_string(lr) + "^2, " + name + "-lit";
        PlotSeries& ps = series[key];
        ps.name = key;
        ps.x.push_back(std::max(t.best.total_ms, 1e-3));
        ps.y.push_back(std::max(e.radiance.rel_rmse, 1e-6));
        save(a.out_dir, "slices_" + name + "_" + std::to_string(n) + "_" + std::to_string(lr), t.image,
             n == a.switch_slices && lr == a.switch_light_res);
      }
    }
    lits.push_back(std::move(lit));
  }

  if (!a.no_lamps) bench_lamps(a, renderer, clouds, camera, back_lit, ref_view, ref_shadow);

  // The optional terms, one at a time, against the same single-scattering reference: their
  // cost, and how far each moves the image from single scattering.
  if (!a.no_switches && !a.no_sun) {
    std::printf("\n## Switches at %d slices, light %d^2 (difference from the single-scattering reference)\n\n",
                a.switch_slices, a.switch_light_res);
    std::printf("| lighting | switch | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|\n");
    for (const Lit& lit : lits) {
      struct Row {
        std::string name;
        render::CloudSliceSettings s;
      };
      render::CloudSliceSettings base;
      base.slices = a.switch_slices;
      base.light_res = a.switch_light_res;
      base.jitter = false;
      base.ambient = false;
      base.blur_cone_rad = 0.0;
      std::vector<Row> rows = {{"none (single scattering, jitter off)", base}};
      rows.push_back({"jitter on", base});
      rows.back().s.jitter = true;
      rows.push_back({"blur on (cone 0.1 rad)", base});
      rows.back().s.blur_cone_rad = 0.1;
      rows.push_back({"ambient on (sky 0.02, 0.025, 0.035)", base});
      rows.back().s.ambient = true;
      rows.push_back({"multiple scattering, 2 octaves", base});
      rows.back().s.multiple.octaves = 2;
      for (const Row& row : rows) {
        const Timed t = timed_render(renderer, camera, lit.light, row.s, a.repeat);
        const CoveredError e = covered_error(t.image, lit.reference);
        std::printf("| %s-lit | %s | %.1f | %.1f | %.4f | %+.4f | %.1e |\n", lit.back ? "back" : "front",
                    row.name.c_str(), t.best.total_ms, t.best_wall_ms, e.radiance.rel_rmse, e.radiance.mean_bias,
                    e.alpha_rmse);
        std::fflush(stdout);
      }
    }
  }

  // Popping: the light sweeps through 90 degrees from the view direction, where the slicer
  // switches between compositing front to back and back to front. Frame-to-frame change =
  // relative RMSE of frame k+1 against frame k (jitter pattern fixed: frame 0).
  if (!a.no_sweep && !a.no_sun) {
    const glm::dvec3 view = glm::normalize(camera.look_at - camera.eye);
    const glm::dvec3 side = glm::normalize(glm::dvec3(0.6, 0.8, 0.0) - glm::dot(glm::dvec3(0.6, 0.8, 0.0), view) * view);
    const int frames = static_cast<int>(std::lround(2.0 * a.sweep_half_deg / a.sweep_step_deg));
    render::CloudSliceSettings s;
    s.slices = a.switch_slices;
    s.light_res = a.switch_light_res;
    s.jitter = a.jitter;
    s.ambient = false;
    std::vector<render::Image> images;
    std::vector<bool> ftb;
    std::vector<double> angle;
    for (int k = 0; k < frames; ++k) {
      const double deg = 90.0 - a.sweep_half_deg + (k + 0.5) * a.sweep_step_deg;
      render::CloudLight light = bench_light(false);
      light.direction_to_light = std::cos(deg * kPi / 180.0) * view + std::sin(deg * kPi / 180.0) * side;
      render::CloudFrameStats st;
      images.push_back(renderer.render(camera, light, s, nullptr, &st));
      ftb.push_back(st.front_to_back);
      angle.push_back(deg);
    }
    std::vector<double> others;
    double at_switch = -1.0, switch_deg = 0.0;
    for (int k = 0; k + 1 < frames; ++k) {
      const double c = render::compare_images(images[k + 1], images[k]).rel_rmse;
      if (ftb[k] != ftb[k + 1]) {
        at_switch = std::max(at_switch, c);
        switch_deg = 0.5 * (angle[k] + angle[k + 1]);
      } else {
        others.push_back(c);
      }
    }
    std::sort(others.begin(), others.end());
    const double median = others.empty() ? 0.0 : others[others.size() / 2];
    std::printf("\n## Popping: light swept %.1f..%.1f degrees from the view direction in %.2f degree steps, %d slices, "
                "light %d^2, jitter %s\n\n",
                angle.front(), angle.back(), a.sweep_step_deg, a.switch_slices, a.switch_light_res,
                a.jitter ? "on (fixed pattern)" : "off");
    if (at_switch < 0) {
      std::printf("no branch switch inside the sweep (front_to_back never changed)\n");
    } else {
      std::printf("| frame-to-frame change | rel. RMSE |\n|---|---:|\n");
      std::printf("| at the switch (%.2f deg) | %.5f |\n| median elsewhere | %.5f |\n| max elsewhere | %.5f |\n",
                  switch_deg, at_switch, median, others.empty() ? 0.0 : others.back());
      std::printf("| ratio switch / median (target <= 2) | %.2f |\n", median > 0 ? at_switch / median : 0.0);
    }
  }
  if (!a.plot.empty()) {
    Plot p;
    p.title = "Clouds, " + std::to_string(a.volume_res) + "^3 noisy sphere, " + std::to_string(width) + "x" +
              std::to_string(height) + ", " + gl->renderer();
    p.x_title = "time per frame (ms): GPU passes; vdb_render: its ray-tracing time";
    p.y_title = "relative RMSE vs CPU reference";
    for (auto& [name, s] : series) p.series.push_back(s);
    write_svg_plot(a.plot, p);
  }
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
