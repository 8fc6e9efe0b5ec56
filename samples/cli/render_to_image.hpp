// `nimbus render`'s clouds as a function that returns the image (the Python module): the same
// flags, parsed and checked as the program does, without the ones that name files or frames.
#pragma once
#include <string>
#include <vector>

#include "nimbus/render/core/image.hpp"
#include "render_clouds.hpp"

namespace nimbus::cli {

// `args`: what would follow `nimbus render` (files, --preset, --scene, --eye...), without -o,
// --preview, --exposure, --view-state and the frame flags other than --time. UsageError for a bad
// or unknown flag (as the program words it), runtime errors as the program's; the image is the
// one `nimbus render` would write to its EXR, in float (row 0 at the top, premultiplied).
// `memory`: clouds held in memory, rendered among the files as the files they would be written to
// (in order of MemoryCloud::position).
render::Image render_clouds_image(const std::vector<std::string>& args, std::vector<MemoryCloud> memory = {});

// A flag it takes, as spelled on the command line ("--slices", "--eye", ...), whether it takes
// a value (a switch does not), its default as `--help` shows it (empty where it has none or
// says it in words) and its help text.
struct ImageFlag {
  std::string name;
  bool takes_value = true;
  std::string default_text;
  std::string help;
};
std::vector<ImageFlag> render_image_flags();

}  // namespace nimbus::cli
