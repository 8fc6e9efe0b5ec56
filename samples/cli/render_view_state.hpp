// `nimbus render --view-state FILE -o OUT.exr`: a viewer state (Ctrl+S, or a screenshot's
// metadata) rendered offline through the viewer's pipeline at full quality; with --spp N, the
// mean of N progressive samples (progressive_frame.hpp), as the viewer shows a still view.
#pragma once
#include <optional>
#include <string>

#include "render_args.hpp"

namespace nimbus::cli {

int run_render_view_state(const std::string& path, const CameraArgs& camera, const std::string& output,
                          const std::string& preview, std::optional<double> exposure, int samples, bool grain_filter);

}  // namespace nimbus::cli
