// What `nimbus render FILE.vdb | --preset NAME` will draw, made from its flags in named stages
// (method and scene, frames and names, optics, lights, renderer settings, presets), every usage
// error found before any work starts.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "nimbus/render/core/cloud_method.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/frame/frame_description.hpp"
#include "render_clouds.hpp"

namespace nimbus::cli {

struct CloudRenderPlan {
  std::string method;                       // as named on the command line ("slices" by default)
  render::CloudMethod cloud_method{};
  // The frame (frame_description.hpp): the scene (none with --scene none) and its sun, the --sun
  // and --lamp lights (the sun first, when there is one), the optics, the camera before framing
  // (the scene's, or 512x512 at vdb_render's fov alone) and the settings (method, slicer,
  // shafts, path tracer).
  render::FrameDescription frame;
  FrameRange range;                         // this run's frames
  std::vector<render::PresetCloud> presets; // --preset, loaded
};

// The plan, or a UsageError naming the flag at fault. Outputs and inputs are checked by the caller.
CloudRenderPlan plan_cloud_render(const CloudRenderArgs& a, const std::string& scene_name, bool scene_given,
                                  const std::string& method_text, bool method_given, const std::string& output,
                                  const std::string& preview, std::optional<double> exposure);

// "R,G,B" or one value for all three; UsageError naming `flag`.
glm::dvec3 parse_colour(const std::string& flag, const std::string& text);

}  // namespace nimbus::cli
