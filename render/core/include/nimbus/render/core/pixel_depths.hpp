// What each pixel of a frame shows, for carrying the frame into the next one
// (temporal_frame.hpp): how far along its ray, and whether clouds or a surface. The frame
// pipeline fills it from its composite when asked (FrameRenderer::render).
#pragma once
#include <cstddef>
#include <vector>

namespace nimbus::render {

struct PixelDepths {
  int width = 0, height = 0;
  // Two floats per pixel, row 0 at the top: the metres from the eye to what carries the pixel's
  // detail, and 1 when that is the clouds (they move with the wind), 0 when it is a surface or
  // the sky. The clouds' alpha-weighted mean distance where their alpha is at least a half, or
  // where any cloud is over the sky (the sky is smooth, the cloud's edge is the detail); else the
  // surface's; else 0, the sky, infinitely far.
  std::vector<float> values;

  bool empty() const { return width == 0 || height == 0; }
  float distance_m(int x, int y) const { return values[2 * (static_cast<std::size_t>(y) * width + x)]; }
  bool on_clouds(int x, int y) const { return values[2 * (static_cast<std::size_t>(y) * width + x) + 1] >= 0.5f; }
};

}  // namespace nimbus::render
