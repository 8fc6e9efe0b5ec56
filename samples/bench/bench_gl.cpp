// `nimbus bench gl`: the device's rates for the work a frame is made of (gl_limits.hpp), at each
// frame size: the limits against which `nimbus bench view` reads its passes' times.
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli.hpp"
#include "cli/render_args.hpp"
#include "gl_limits.hpp"
#include "nimbus/render/gl/context.hpp"

namespace nimbus::cli {
namespace {

struct BenchGlArgs {
  std::string sizes = "640x360,1280x720";
  int repeats = 3;
};

int run_bench_gl(const BenchGlArgs& a) {
  const std::vector<std::pair<int, int>> sizes = parse_resolutions("--sizes", a.sizes);
  if (a.repeats < 1 || a.repeats > 100) throw UsageError("--repeats: must be in [1, 100]");
  const auto gl = render::GlContext::create_headless();
  std::printf("# nimbus bench gl: %s; each rate the best of %d runs, glFinish around each\n\n", gl->renderer().c_str(), a.repeats);
  print_gl_limits_header();
  for (const auto& [w, h] : sizes) print_gl_limits_row(measure_gl_limits(w, h, a.repeats));
  return 0;
}

}  // namespace

void print_gl_limits_header() {
  std::printf("| size | fragments shaded, M/s (RGBA32F) | fragments blended, M/s | 3D-texture samples, M/s (trilinear, R16F) | "
              "pixels read back, M/s (RGBA32F) | slice round trips, 1/s |\n|---|---:|---:|---:|---:|---:|\n");
}

void print_gl_limits_row(const GlLimits& l) {
  std::printf("| %dx%d | %.0f | %.0f | %.0f | %.0f | %.0f |\n", l.width, l.height, l.fragments_per_s * 1e-6, l.blended_per_s * 1e-6,
              l.samples_3d_per_s * 1e-6, l.readback_pixels_per_s * 1e-6, l.slice_round_trips_per_s);
  std::fflush(stdout);
}

void add_bench_gl(CLI::App& bench, Action& action) {
  auto a = std::make_shared<BenchGlArgs>();
  CLI::App* cmd = bench.add_subcommand("gl", "The device's rates for a frame's work: fragments shaded and blended, 3D-texture samples, pixels read back");
  cmd->add_option("--sizes", a->sizes, "Comma-separated frame sizes WxH")->capture_default_str();
  cmd->add_option("--repeats", a->repeats, "Timed runs per rate; the best is kept")->capture_default_str();
  cmd->callback([&action, a] { action = [a] { return run_bench_gl(*a); }; });
}

}  // namespace nimbus::cli
