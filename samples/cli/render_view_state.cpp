// `nimbus render --view-state` (render_view_state.hpp).
#include "render_view_state.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "outputs.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/sky/progressive_frame.hpp"
#include "nimbus/render/sky/sky_keyframes.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "nimbus/render/frame/sky_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"

namespace nimbus::cli {

int run_render_view_state(const std::string& path, const CameraArgs& camera, const std::string& output,
                          const std::string& preview, std::optional<double> exposure, int samples, bool grain_filter) {
  int width = 960, height = 540;
  if (samples < 1 || samples > 4096) throw UsageError("--spp: must be in [1, 4096] with --view-state, got " + std::to_string(samples));
  if (!camera.res.empty()) std::tie(width, height) = parse_resolution("--res", camera.res);
  check_exposure(exposure);
  // One picture: a frame field would be written literally (a file named "o.%04d.exr").
  for (const auto& [flag, p] : {std::pair<std::string, std::string>{"-o", output}, {"--preview", preview}})
    if (p.find('%') != std::string::npos)
      throw UsageError(flag + ": '" + echo(p) + "' holds a %: a view state renders one picture, not a sequence");
  int version = 0;
  render::ViewState state = render::load_view_state(path, &version);
  if (!grain_filter) state.grain_filter.on = false;
  const std::string version_note = render::view_state_version_note(path, version);  // said once every check has passed
  // The frame is rendered at the state's render scale, as the viewer draws it.
  const auto [frame_w, frame_h] = render::scaled_frame_size(width, height, state.render_scale);
  if (frame_w < 1 || frame_h < 1)
    throw UsageError("--res " + std::to_string(width) + "x" + std::to_string(height) + " at the state's renderer.render_scale " +
                     number_text(state.render_scale) + " is below one pixel (" + std::to_string(frame_w) + "x" +
                     std::to_string(frame_h) + "); give a larger --res");
  render::check_sky_cloud_files(state.sky);
  check_outputs({{"-o", output}, {"--preview", preview}},
                RunInputs().file("--view-state", path).sky(state.sky, "--view-state '" + path + "' sky"));
  if (!version_note.empty()) std::cerr << "note: " << version_note << "\n";
  checks_done();
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<render::GlContext> gl;
  try {
    gl = render::GlContext::create_headless();
  } catch (const render::GlUnavailable& e) {
    throw std::runtime_error(std::string("--view-state needs OpenGL: ") + e.what());
  }
  render::SkyRenderer renderer(state);
  render::SkyFrameInfo info;
  render::ProgressiveFrame mean;
  render::PixelDepths depths;  // the last frame's, to guide the grain filter (read back for it alone)
  naming_gpu_memory("--res", width, height, [&] {
    for (int i = 0; i < samples; ++i) {
      render::FrameQuality quality;
      quality.sample = render::progressive_sample(static_cast<unsigned>(i));
      mean.add(renderer.render(state, width, height, quality, true, nullptr, &info, i + 1 == samples ? &depths : nullptr),
               "the state");
    }
    return 0;
  });
  const render::Image image = render::still_picture(mean.mean(), mean.samples(), depths, state.grain_filter, state.slices.jitter);
  render::PreviewOptions po;
  po.exposure_stops = exposure ? *exposure : state.exposure_stops;
  write_image_files(output, preview, image, po);
  warn_half_float_clipping(image, output, "the state's lights or optics.extinction");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::string size = std::to_string(info.width) + "x" + std::to_string(info.height);
  if (info.width != width || info.height != height)
    size += " (--res " + std::to_string(width) + "x" + std::to_string(height) + " at render scale " + number_text(state.render_scale) + ")";
  if (samples > 1) size += ", " + std::to_string(samples) + " samples";
  std::fprintf(stderr, "%s: view state %s, %s, %.2f s\n", echo(output, 200).c_str(), echo(path, 200).c_str(), size.c_str(), seconds);
  return 0;
}

}  // namespace nimbus::cli
