// `nimbus render --view-state` (render_view_state.hpp).
#include "render_view_state.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "cli.hpp"
#include "outputs.hpp"
#include "nimbus/render/core/view_state.hpp"
#include "nimbus/render/frame/sky_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"

namespace nimbus::cli {

int run_render_view_state(const std::string& path, const CameraArgs& camera, const std::string& output,
                          const std::string& preview, std::optional<double> exposure) {
  int width = 960, height = 540;
  if (!camera.res.empty()) std::tie(width, height) = parse_resolution("--res", camera.res);
  check_exposure(exposure);
  const render::ViewState state = render::load_view_state(path);
  check_outputs({{"-o", output}, {"--preview", preview}}, {{"--view-state", path}});
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<render::GlContext> gl;
  try {
    gl = render::GlContext::create_headless();
  } catch (const render::GlUnavailable& e) {
    throw std::runtime_error(std::string("--view-state needs OpenGL: ") + e.what());
  }
  render::SkyRenderer renderer(state);
  const render::Image image = renderer.render(state, width, height, render::FrameQuality{}, true);
  render::PreviewOptions po;
  po.exposure_stops = exposure ? *exposure : state.exposure_stops;
  write_image_files(output, preview, image, po);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%s: view state %s, %dx%d, %.2f s\n", output.c_str(), path.c_str(), width, height, seconds);
  return 0;
}

}  // namespace nimbus::cli
