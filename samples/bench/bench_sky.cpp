// `nimbus bench sky`: what the physical sky costs and how far its tables are from the
// brute-force reference: each table's build time on the CPU, the
// frame's cost with the physical sky against the same frame with the old gradient sky (the
// anchor), and the tables' sky radiance against render/reference/atmosphere_reference.hpp over
// a set of view directions, for several sun elevations.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "cli/render_args.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/reference/atmosphere_reference.hpp"

namespace nimbus::cli {
namespace {

struct BenchSkyArgs {
  std::string elevations = "60,33,10,2,-3";
  std::string res = "640x360";
  int repeat = 3;
};

std::vector<double> parse_doubles(const std::string& flag, const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::optional<double> x = nimbus::parse_double(item);
    if (!x || !std::isfinite(*x) || *x < -10.0 || *x > 90.0) throw UsageError(flag + ": '" + item + "' is not an elevation in [-10, 90] degrees");
    v.push_back(*x);
  }
  if (v.empty()) throw UsageError(flag + ": give at least one elevation");
  return v;
}

int run_bench_sky(const BenchSkyArgs& a) {
  const auto [w, h] = parse_resolution("--res", a.res);
  const std::vector<double> elevations = parse_doubles("--elevations", a.elevations);
  if (a.repeat < 1 || a.repeat > 100) throw UsageError("--repeat: must be in [1, 100]");
  const auto gl = render::GlContext::create_headless();
  std::printf("# nimbus bench sky: Hillaire (2020) tables against the brute-force reference, %s\n", gl->renderer().c_str());
  std::printf("# tables: CPU ms on this machine (transmittance and multiple scattering once per atmosphere; sky view and\n"
              "#   aerial perspective once per sun position); error: the table's sky radiance against the reference\n"
              "#   over 8 view directions 12-80 degrees above the horizon, and over 4 at 3 and 8 degrees\n"
              "#   (worst channel, relative); frame: the sky scene with the cumulus-mediocris preset, %dx%d, GPU ms\n"
              "#   of the scene (shafts and sky) and the composite (clouds, fog and aerial perspective), best of %d,\n"
              "#   against the same frame with the gradient sky of before (no tables, no aerial perspective)\n\n",
              w, h, a.repeat);
  std::printf("| sun elevation | transmittance ms | multiple scattering ms | sky view ms | aerial perspective ms | "
              "max error | max error near horizon | frame scene ms | composite ms | gradient scene ms | gradient composite ms |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  const render::Atmosphere atm;
  render::PresetCloud preset = render::load_preset_cloud("cumulus-mediocris");
  render::CloudOptics optics;
  const std::vector<render::CloudVolume> clouds = {render::generate_preset_cloud(preset, std::nullopt, 0.0, optics)};
  for (double el : elevations) {
    const glm::dvec3 sun = render::sun_direction(el, 120.0);
    const auto tables = render::build_atmosphere_tables(atm, render::AtmosphereView{2.0, sun, 40000.0});
    double worst = 0.0, worst_low = 0.0;
    const glm::dvec3 sh = glm::length(glm::dvec2(sun.x, sun.z)) > 0 ? glm::normalize(glm::dvec3(sun.x, 0, sun.z)) : glm::dvec3(1, 0, 0);
    const glm::dvec3 side{-sh.z, 0.0, sh.x};
    for (double vel : {80.0, 45.0, 20.0, 12.0, 8.0, 3.0}) {
      for (double az : {0.0, 90.0}) {
        const double e = vel * M_PI / 180.0, t = az * M_PI / 180.0;
        const glm::dvec3 d = std::cos(e) * (std::cos(t) * sh + std::sin(t) * side) + glm::dvec3(0, std::sin(e), 0);
        const glm::dvec3 ref = render::reference_sky(atm, render::AtmosphereRay{2.0, sun, d}).inscattered_w_sr_m2;
        const glm::dvec3 got = render::table_sky_radiance(*tables, d);
        double err = 0.0;
        for (int c = 0; c < 3; ++c) err = std::max(err, ref[c] > 0 ? std::abs(got[c] - ref[c]) / ref[c] : 0.0);
        (vel >= 12.0 ? worst : worst_low) = std::max(vel >= 12.0 ? worst : worst_low, err);
      }
    }
    // The frame, with the physical sky and with the gradient sky of the same zenith and horizon.
    double frame[2][2];
    for (int kind = 0; kind < 2; ++kind) {
      render::Scene scene = render::make_scene("sky");
      const render::Daylight d = render::daylight(sun);
      scene.sky = d.sky;
      if (kind == 1) scene.sky->atmosphere = nullptr;
      render::Light light{sun, d.cloud_sun_irradiance_w_m2};
      render::FrameSettings fs;
      render::FrameRenderer fr(scene, light, fs);
      fr.set_clouds(clouds);
      render::Camera cam = scene.camera;
      cam.width = w;
      cam.height = h;
      fr.render(cam);
      double best_scene = 1e300, best_composite = 1e300;
      for (int r = 0; r < a.repeat; ++r) {
        render::FrameStats st;
        fr.render(cam, &st);
        best_scene = std::min(best_scene, st.scene.total_ms);
        best_composite = std::min(best_composite, st.clouds.composite_ms);
      }
      frame[kind][0] = best_scene;
      frame[kind][1] = best_composite;
    }
    std::printf("| %.0f | %.1f | %.1f | %.1f | %.1f | %.4f | %.4f | %.1f | %.1f | %.1f | %.1f |\n", el, tables->timing.transmittance_ms,
                tables->timing.multiple_scattering_ms, tables->timing.sky_view_ms, tables->timing.aerial_perspective_ms, worst, worst_low,
                frame[0][0], frame[0][1], frame[1][0], frame[1][1]);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

void add_bench_sky(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchSkyArgs>();
  CLI::App* cmd = bench.add_subcommand("sky", "The physical sky: table build times, frame cost, and error against the brute-force reference");
  cmd->add_option("--elevations", a->elevations, "Comma-separated sun elevations, degrees in [-10, 90]")->capture_default_str();
  cmd->add_option("--res", a->res, "Frame size WxH")->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "Frames timed per case (the best is reported)")->capture_default_str();
  cmd->callback([&action, a] { action = [a] { return run_bench_sky(*a); }; });
}

}  // namespace nimbus::cli
