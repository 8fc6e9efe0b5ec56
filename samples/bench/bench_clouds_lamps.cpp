// The lamp rows of `nimbus bench clouds` (bench_clouds.hpp): the noisy sphere lit by a lamp at a
// distance along the sun's front- and back-lit directions (intensity d^2, so about 1 W m^-2 at the
// centre), slicer against the CPU reference; two lamps at once against one pass each dropped; and
// the steam of the `steam-lamp` scene.
#include <chrono>
#include <cstdio>
#include <map>
#include <optional>

#include "bench_clouds.hpp"
#include "cli/cli.hpp"
#include "cli/render_args.hpp"
#include "nimbus/app/bench_clouds_scene.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::cli::bench_clouds {
namespace {

// What every lamp row measures with.
struct LampRows {
  const BenchCloudsArgs& a;
  render::CloudRenderer& renderer;
  const std::vector<render::CloudVolume>& clouds;
  const render::Camera& camera;
  const std::vector<bool>& back_lit;
  double ref_view, ref_shadow;
};

// A lamp at distance d along the front- or back-lit direction, intensity d^2 W/sr.
render::Light lamp(bool back, double d) {
  const glm::dvec3 dir = glm::normalize(app::bench_light(back).direction_to_sun);
  return render::point_light(d * dir, glm::dvec3(d * d));
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

// One lamp at each distance, front- and back-lit: the slice sweep at the first distance, the switch
// rows' slice count at the others. Returns the references at the first distance.
std::map<bool, render::Image> single_lamp_rows(const LampRows& r) {
  const BenchCloudsArgs& a = r.a;
  const std::vector<double> distances = lamp_distances(a);
  const std::vector<int> slice_counts = int_list("--lamp-slices", a.lamp_slices, 2, 4096);
  std::printf("\n## Lamps: a point light at distance d from the sphere's centre (radius 0.47) along the front- or "
              "back-lit direction, intensity d^2 W/sr\n\n");
  std::printf("| lighting | d (m) | slices, light | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|\n");
  std::map<bool, render::Image> mid_reference;  // at the first distance, for the two-lamp rows
  for (const bool back : r.back_lit) {
    for (std::size_t di = 0; di < distances.size(); ++di) {
      const double d = distances[di];
      const std::vector<render::Light> lights = {lamp(back, d)};
      const auto t0 = std::chrono::steady_clock::now();
      const render::Image ref = reference_with_progress(r.clouds, r.camera, lights, r.ref_view, r.ref_shadow,
                                                        std::string("reference lamp ") + (back ? "back" : "front"));
      const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("| %s-lit | %.2f | reference (CPU, double), %g / %g voxel | | %.0f | 0 | 0 | 0 |\n", back ? "back" : "front",
                  d, r.ref_view, r.ref_shadow, 1000.0 * ref_s);
      if (di == 0) mid_reference[back] = ref;
      for (const int n : slice_counts) {
        if (di > 0 && n != a.switch_slices) continue;  // the slice sweep at the first distance only
        const render::CloudSliceSettings s = lamp_row_settings(a, n);
        const Timed t = timed_render(r.renderer, r.camera, lights, s, a.repeat);
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
  return mid_reference;
}

// Two lamps at the first distance: one pass each, against the sum of their references; with
// max_lights 1 the weaker one is left out, and its share is the error.
void two_lamp_rows(const LampRows& r, std::map<bool, render::Image>& mid_reference) {
  const BenchCloudsArgs& a = r.a;
  if (mid_reference.size() != 2) return;
  const double d = lamp_distances(a).front();
  const std::vector<render::Light> both = {lamp(false, d), lamp(true, d)};
  render::Image sum = mid_reference[false];
  for (int y = 0; y < sum.height; ++y)
    for (int x = 0; x < sum.width; ++x)
      for (int c = 0; c < 3; ++c) sum.pixel(x, y)[c] += mid_reference[true].pixel(x, y)[c];
  std::printf("\n| two lamps (front and back, d %.2f) | passes | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n", d);
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  for (const int max_lights : {2, 1}) {
    render::CloudSliceSettings s = lamp_row_settings(a, a.switch_slices);
    s.max_lights = max_lights;
    const Timed t = timed_render(r.renderer, r.camera, both, s, a.repeat);
    const CoveredError e = covered_error(t.image, sum);
    std::printf("| max_lights %d | %d | %.1f | %.1f | %.4f | %+.4f | %.1e |\n", max_lights, t.best.light_passes,
                t.best.total_ms, t.best_wall_ms, e.radiance.rel_rmse, e.radiance.mean_bias, e.alpha_rmse);
    std::fflush(stdout);
  }
}

// The steam of the teacup (Hoffmann 2007) under the street lamp (scene steam-lamp), clouds alone.
void steam_rows(const LampRows& r) {
  const BenchCloudsArgs& a = r.a;
  const std::vector<int> slice_counts = int_list("--lamp-slices", a.lamp_slices, 2, 4096);
  const render::Scene scene = render::make_scene("steam-lamp");
  render::CloudOptics optics;
  optics.extinction_per_m = *scene.cloud_extinction_per_m;
  optics.phase = render::kCloudPhase;  // nimbus render's default look
  const std::vector<render::CloudVolume> steam = {
      render::generate_preset_cloud(render::load_preset_cloud("steam"), a.steam_voxel, 0.0, optics)};
  render::Camera cam = scene.camera;
  cam.width = r.camera.width;
  cam.height = r.camera.height;
  const std::vector<render::Light> lights = {
      scene.lamps[0]};
  const auto t0 = std::chrono::steady_clock::now();
  const render::Image ref = reference_with_progress(steam, cam, lights, r.ref_view, r.ref_shadow, "reference steam");
  const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  render::CloudRenderer steam_renderer(steam, a.format == "r32f" ? GL_R32F : GL_R16F);
  std::printf("\n## Steam under the lamp (scene steam-lamp, preset steam at %g m voxels: %dx%dx%d, extinction %g per "
              "metre, dual-lobe phase 0.7/-0.25/0.8), clouds alone\n\n",
              a.steam_voxel, static_cast<int>(steam[0].box.size[0]), static_cast<int>(steam[0].box.size[1]),
              static_cast<int>(steam[0].box.size[2]), optics.extinction_per_m);
  std::printf("| renderer | setting | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|\n");
  std::printf("| reference (CPU, double) | %g / %g voxel | | %.0f | 0 | 0 | 0 |\n", r.ref_view, r.ref_shadow, 1000.0 * ref_s);
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

}  // namespace

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

void bench_lamps(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const std::vector<render::CloudVolume>& clouds,
                 const render::Camera& camera, const std::vector<bool>& back_lit, double ref_view, double ref_shadow) {
  const LampRows rows{a, renderer, clouds, camera, back_lit, ref_view, ref_shadow};
  std::map<bool, render::Image> mid_reference = single_lamp_rows(rows);
  two_lamp_rows(rows, mid_reference);
  if (a.steam_voxel > 0.0) steam_rows(rows);
}

}  // namespace nimbus::cli::bench_clouds
