// `nimbus bench view`'s tables of the accumulated frames (render/sky/temporal_frame.hpp): what
// each level gives up alone and accumulated on a still view, and what accumulating earns while
// the camera turns, each against the full frame's grain-free mean.
#pragma once
#include <utility>
#include <vector>

#include "nimbus/render/sky/view_state.hpp"
#include "viewer/viewer.hpp"

namespace nimbus::cli {

// Every level of kTemporalQualityLevels on `start` (time paused): one frame, and 8 jittered
// frames accumulated, against the full-quality frame and against its still view's mean.
void print_accumulated_levels(const render::ViewState& start, const viewer::ViewerOptions& options,
                              const std::vector<std::pair<int, int>>& sizes);

// The camera turning about its target at 0, 1 and 1.8 degrees a frame (time paused), 16 frames
// at the lowest accumulated level: the accumulated frame and the last frame alone against the
// last pose's still-view mean.
void print_accumulated_motion(const render::ViewState& start, const std::vector<std::pair<int, int>>& sizes);

}  // namespace nimbus::cli
