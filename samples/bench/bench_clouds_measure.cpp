// The measuring helpers of `nimbus bench clouds` (bench_clouds.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>

#include "bench_clouds.hpp"
#include "cli/cli.hpp"
#include "cli/progress.hpp"
#include "cli/render_args.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"

namespace nimbus::cli::bench_clouds {

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

Timed timed_render(render::CloudRenderer& r, const render::Camera& cam, const std::vector<render::Light>& lights,
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

Timed timed_render(render::CloudRenderer& r, const render::Camera& cam, const render::Light& light,
                   const render::CloudSliceSettings& s, int repeat) {
  return timed_render(r, cam, std::vector<render::Light>{light}, s, repeat);
}

render::Image reference_with_progress(const std::vector<render::CloudVolume>& clouds, const render::Camera& cam,
                                      const std::vector<render::Light>& light, double view_step,
                                      double shadow_step, const std::string& what) {
  Progress progress(what);
  render::CloudReferenceSettings s;
  s.view_step_voxels = view_step;
  s.shadow_step_voxels = shadow_step;
  s.progress = [&](double f) { progress.update(f); };
  return render::render_cloud_reference(clouds, cam, light, s);
}

}  // namespace nimbus::cli::bench_clouds
