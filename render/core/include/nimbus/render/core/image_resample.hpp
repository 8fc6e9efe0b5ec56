// An image scaled up to another size with bilinear filtering, pixel centres at +0.5: what a
// display's linear filter does with a frame drawn small (the viewer's adaptive quality), so
// that its error can be measured against the full frame.
#pragma once
#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

// `src` at w x h (each at least 1); the metadata is kept. Returns src unchanged at its own size.
Image upscale_bilinear(const Image& src, int w, int h);

}  // namespace nimbus::render
