// A linear RGBA float image with premultiplied alpha, row 0 at the top: what every renderer
// in nimbus produces and what the EXR and PNG writers take.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
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

// Throws std::invalid_argument, starting with `what`, when the image is empty (width or height
// <= 0), its data size is not width * height * 4, or a value is NaN or Inf or (unless
// allow_negative) negative; the message names the pixel (x, y) and the channel (R, G, B or A).
void check_image(const Image& image, std::string_view what, bool allow_negative = false);

}  // namespace nimbus::render
