// Bilinear upscaling (image_resample.hpp).
#include "nimbus/render/core/image_resample.hpp"

#include <algorithm>
#include <stdexcept>

namespace nimbus::render {

Image upscale_bilinear(const Image& src, int w, int h) {
  if (src.width < 1 || src.height < 1 || w < 1 || h < 1)
    throw std::invalid_argument("upscale_bilinear: the image and the size must be at least 1x1");
  if (src.width == w && src.height == h) return src;
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double sx = std::clamp((x + 0.5) * src.width / w - 0.5, 0.0, src.width - 1.0);
      const double sy = std::clamp((y + 0.5) * src.height / h - 0.5, 0.0, src.height - 1.0);
      const int x0 = static_cast<int>(sx), y0 = static_cast<int>(sy);
      const int x1 = std::min(x0 + 1, src.width - 1), y1 = std::min(y0 + 1, src.height - 1);
      const double fx = sx - x0, fy = sy - y0;
      for (int c = 0; c < 4; ++c)
        out.pixel(x, y)[c] = static_cast<float>((1 - fy) * ((1 - fx) * src.pixel(x0, y0)[c] + fx * src.pixel(x1, y0)[c]) +
                                                fy * ((1 - fx) * src.pixel(x0, y1)[c] + fx * src.pixel(x1, y1)[c]));
    }
  out.metadata = src.metadata;
  return out;
}

}  // namespace nimbus::render
