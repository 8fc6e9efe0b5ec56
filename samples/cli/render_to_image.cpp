// `nimbus render`'s clouds, returned as an image (render_to_image.hpp).
#include "render_to_image.hpp"

#include <memory>

#include "cli.hpp"
#include "flag_checks.hpp"
#include "render_args.hpp"
#include "render_clouds.hpp"
#include "render_modes.hpp"

namespace nimbus::cli {
namespace {

struct ImageArgs {
  std::string scene = "sky", method = "slices";
  bool no_surface_airlight = false;
  CameraArgs camera;
  CloudRenderArgs clouds;
};

// The command: `nimbus render`'s own registrations, less the file and frame flags.
std::unique_ptr<CLI::App> image_command(ImageArgs& a) {
  auto cmd = std::make_unique<CLI::App>("nimbus render, to an image", "render");
  add_scene_options(cmd.get(), a.scene, a.method, a.no_surface_airlight);
  add_cloud_render_options(cmd.get(), a.clouds);
  add_camera_options(cmd.get(), a.camera);
  for (const char* flag : {"--frames", "--fps", "--time-scale", "--many-frames", "--start-frame", "--frame-from-env", "--chunk"})
    cmd->remove_option(cmd->get_option(flag));
  return cmd;
}

}  // namespace

std::vector<ImageFlag> render_image_flags() {
  ImageArgs a;
  const auto cmd = image_command(a);
  std::vector<ImageFlag> flags;
  for (const CLI::Option* o : cmd->get_options())
    if (o->get_name() != "--help" && o->get_name() != "file")
      flags.push_back({o->get_name(), o->get_expected_max() != 0, o->get_default_str(), o->get_description()});
  return flags;
}

render::Image render_clouds_image(const std::vector<std::string>& args, std::vector<MemoryCloud> memory) {
  ImageArgs a;
  const auto cmd = image_command(a);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    cmd->parse(reversed);
  } catch (const CLI::Success&) {  // --help or --version among the values: not a request for an image
    throw UsageError("render: --help and --version are not options of an image render");
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  refuse_empty_values(*cmd);
  check_render_flags(*cmd, kRenderClouds);
  a.clouds.memory = std::move(memory);
  if (a.clouds.files.empty() && a.clouds.presets.empty() && a.clouds.memory.empty())
    throw UsageError("nothing to render: give a volume, a VDB file or --preset");
  for (const CLI::Option* o : cmd->get_options())
    if (o->count() > 0) a.clouds.given.insert(o->get_name());
  a.clouds.surface_airlight = !a.no_surface_airlight;
  render::Image out;
  run_render_clouds(a.clouds, a.scene, cmd->count("--scene") > 0, a.method, cmd->count("--method") > 0, a.camera, "", "", std::nullopt,
                    [&](render::Image& image, int) { out = std::move(image); });
  return out;
}

}  // namespace nimbus::cli
