// The switch rows and the popping sweep of `nimbus bench clouds` (bench_clouds.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench_clouds.hpp"
#include "nimbus/app/bench_clouds_scene.hpp"

namespace nimbus::cli::bench_clouds {

// The optional terms, one at a time, against the same single-scattering reference: their cost,
// and how far each moves the image from single scattering.
void switch_rows(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const render::Camera& camera,
                 const std::vector<Lit>& lits) {
  std::printf("\n## Switches at %d slices, light %d^2 (difference from the single-scattering reference)\n\n",
              a.switch_slices, a.switch_light_res);
  std::printf("| lighting | switch | GPU ms | wall ms | rel. RMSE | bias | alpha RMSE |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|\n");
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
  for (const Lit& lit : lits) {
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
void sweep_rows(const BenchCloudsArgs& a, render::CloudRenderer& renderer, const render::Camera& camera) {
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
    render::Light light = app::bench_light(false);
    light.direction_to_sun = std::cos(deg * kPi / 180.0) * view + std::sin(deg * kPi / 180.0) * side;
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

}  // namespace nimbus::cli::bench_clouds
