// What each pixel of a frame shows, for carrying the frame into the next one
// (temporal_frame.hpp): how far along its ray, and whether clouds or a surface. The frame
// pipeline fills it from its composite when asked (FrameRenderer::render).
#pragma once
#include <cstddef>
#include <vector>

namespace nimbus::render {

struct PixelDepths {
  int width = 0, height = 0;
  // Two floats per pixel, row 0 at the top: the metres from the eye to what the pixel mostly
  // shows (the clouds' alpha-weighted mean distance where their alpha is at least a half, else
  // the surface's; 0 for the sky, which is infinitely far), and the clouds' alpha in [0, 1].
  std::vector<float> values;

  bool empty() const { return width == 0 || height == 0; }
  float distance_m(int x, int y) const { return values[2 * (static_cast<std::size_t>(y) * width + x)]; }
  float cloud_alpha(int x, int y) const { return values[2 * (static_cast<std::size_t>(y) * width + x) + 1]; }
};

}  // namespace nimbus::render
