// check_image: the refusals shared by the EXR and PNG writers and the image comparison.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/image.hpp"

namespace nimbus::render {
namespace {

std::string format(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
  return buf;
}

}  // namespace

void check_image(const Image& image, std::string_view what, bool allow_negative) {
  const std::string name(what);
  if (image.width <= 0 || image.height <= 0) {
    throw std::invalid_argument(name + ": empty image (" + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + ")");
  }
  const std::size_t expected = static_cast<std::size_t>(image.width) * image.height * 4;
  if (image.rgba.size() != expected) {
    throw std::invalid_argument(name + ": image is " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " but holds " +
                                std::to_string(image.rgba.size()) + " values instead of " +
                                std::to_string(expected));
  }
  static constexpr char kChannel[] = "RGBA";
  for (std::size_t i = 0; i < expected; ++i) {
    const float v = image.rgba[i];
    const bool finite = std::isfinite(v);
    if (finite && (allow_negative || v >= 0.0f)) continue;
    const std::size_t p = i / 4;
    throw std::invalid_argument(name + ": pixel (" + std::to_string(p % image.width) + ", " +
                                std::to_string(p / image.width) + ") channel " + kChannel[i % 4] +
                                " is " + (finite ? format(v) : std::isnan(v) ? "NaN" : "Inf") +
                                (finite ? " (negative)" : ""));
  }
}

}  // namespace nimbus::render
