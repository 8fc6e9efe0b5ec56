// A still view drawn again and again and averaged: each sample moves the rays by its own
// sub-pixel offset and shifts the slicer's blue-noise jitter, so the running mean loses the
// grain of one frame and converges to the pixel-box-filtered (supersampled) frame. The viewer
// shows the mean while nothing moves; `nimbus render --view-state --samples N` writes it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

// Sample `index` of a still view: sample 0 is the plain frame (no offset, the jitter of frame 0);
// the others follow the R2 sequence (Roberts 2018) over the pixel, so any run of n samples
// covers the pixel evenly.
struct ProgressiveSample {
  glm::dvec2 pixel_offset{0.0};  // Camera::pixel_offset, each in [-0.5, 0.5)
  unsigned jitter_frame = 0;     // CloudSliceSettings::frame
};
ProgressiveSample progressive_sample(unsigned index);

// The supersampled frame a still view's mean converges to, from a frame drawn `factor` times
// larger on each side: each pixel the mean of its factor x factor block (the pixel's box
// filter). Throws std::invalid_argument when factor < 1 or a side is not a multiple of it.
Image box_downsample(const Image& fine, int factor);

class ProgressiveFrame {
 public:
  // Adds a frame to the mean and returns the mean. A frame of another size or `key` (what was
  // drawn: the state, the light, the quality) starts a new mean. Throws std::invalid_argument
  // (naming the frame) for an empty or non-finite frame; the mean is then left as it was.
  const Image& add(const Image& frame, const std::string& key);
  void reset();
  // Frames in the mean, which is also the index of the next sample to draw.
  unsigned samples() const { return samples_; }
  const std::string& key() const { return key_; }
  const Image& mean() const { return mean_; }

 private:
  std::string key_;
  unsigned samples_ = 0;
  std::vector<double> sum_;  // per pixel and channel, so a long mean loses no precision
  Image mean_;
};

}  // namespace nimbus::render
