// Progressive samples of a still view and their running mean (progressive_frame.hpp).
#include "nimbus/render/sky/progressive_frame.hpp"

#include <cmath>
#include <stdexcept>

namespace nimbus::render {

ProgressiveSample progressive_sample(unsigned index) {
  if (index == 0) return {};
  // R2: the plastic number's reciprocals as the two additive steps, centred on the pixel.
  constexpr double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
  const double n = static_cast<double>(index);
  ProgressiveSample s;
  s.pixel_offset = {n * a1 - std::floor(n * a1) - 0.5, n * a2 - std::floor(n * a2) - 0.5};
  s.jitter_frame = index;
  return s;
}

Image box_downsample(const Image& fine, int factor) {
  if (factor < 1 || fine.width % factor != 0 || fine.height % factor != 0)
    throw std::invalid_argument("box_downsample: a " + std::to_string(fine.width) + "x" + std::to_string(fine.height) +
                                " frame is not " + std::to_string(factor) + " times a whole frame on each side");
  Image out(fine.width / factor, fine.height / factor);
  const double inv = 1.0 / (static_cast<double>(factor) * factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += fine.pixel(factor * x + i, factor * y + j)[c];
        out.pixel(x, y)[c] = static_cast<float>(sum * inv);
      }
  out.metadata = fine.metadata;
  return out;
}

void ProgressiveFrame::reset() {
  key_.clear();
  samples_ = 0;
  sum_.clear();
  mean_ = Image();
}

const Image& ProgressiveFrame::add(const Image& frame, const std::string& key) {
  check_image(frame, "progressive frame");
  if (key != key_ || frame.width != mean_.width || frame.height != mean_.height) {
    reset();
    key_ = key;
    sum_.assign(frame.rgba.size(), 0.0);
  }
  ++samples_;
  const double inv = 1.0 / samples_;
  mean_.width = frame.width;
  mean_.height = frame.height;
  mean_.rgba.resize(frame.rgba.size());
  for (std::size_t i = 0; i < frame.rgba.size(); ++i) {
    sum_[i] += frame.rgba[i];
    mean_.rgba[i] = static_cast<float>(sum_[i] * inv);
  }
  mean_.metadata = frame.metadata;
  mean_.metadata["progressive_samples"] = std::to_string(samples_);
  return mean_;
}

}  // namespace nimbus::render
