// A linear RGBA float image with premultiplied alpha, row 0 at the top: what every renderer
// in nimbus produces and what the EXR and PNG writers take.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace nimbus::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4, premultiplied, linear radiance (W sr^-1 m^-2)
  // Written into the EXR header as string attributes (camera, light, medium, method, ...).
  std::map<std::string, std::string> metadata;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0.0f) {}
  float* pixel(int x, int y) { return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  const float* pixel(int x, int y) const {
    return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
};

}  // namespace nimbus::render
