// What `nimbus render` was asked for, and which flags apply to it: a scene alone, clouds (FILE.vdb
// or --preset, over a scene or alone), or a viewer state (--view-state).
#pragma once
#include "cli.hpp"

namespace nimbus::cli {

enum RenderMode : unsigned { kRenderScene = 1u, kRenderClouds = 2u, kRenderViewState = 4u };

// UsageError "--slices: applies to clouds (FILE.vdb or --preset), not to a scene alone" for the
// first flag given on `render` that does not apply to `mode`.
void check_render_flags(const CLI::App& render, RenderMode mode);

}  // namespace nimbus::cli
