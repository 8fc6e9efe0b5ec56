// Frames drawn small and jittered while the view moves, accumulated into a full-size frame:
// temporal upsampling with reprojection (Karis 2014; Unreal's TAAU; Nubis's 1-in-16 traces,
// Schneider 2015). Each new frame's pixels land where their sub-pixel jitter put them; the last
// output is carried into the new view through each pixel's depth (pixel_depths.hpp, the
// clouds moved by the wind), clamped to the new frame's neighbourhood so that what moved or
// appeared does not smear, and blended with the new samples by how near each one falls. The
// viewer shows it while the camera, the sun or the clock move (docs/viewer.md).
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/core/pixel_depths.hpp"

namespace nimbus::render {

struct TemporalSettings {
  // The most weight a pixel's history may hold, in samples that fell on the pixel's centre:
  // a new sample there takes at least 1 / (1 + max_history) of it. (0, 1e6].
  double max_history = 6.0;
};

void validate(const TemporalSettings& settings);

// The i-th frame's sub-pixel offset (Camera::pixel_offset, in the small frame's pixels) and
// slicer jitter: the R2 sequence again (progressive_sample), so any run of frames covers the
// pixel evenly.
glm::dvec2 temporal_pixel_offset(unsigned index);

class TemporalFrame {
 public:
  explicit TemporalFrame(TemporalSettings settings = {});

  // Adds `frame`, drawn through `camera` (its size and pixel_offset; any size up to the
  // output's), with its `depths` (the frame's size, or empty: everything infinitely far), and
  // returns the frame of `camera` at out_width x out_height without the offset.
  // `cloud_shift_m`: how far the clouds moved since the last frame (the wind), render space.
  // A new output size starts again from the frame alone, upsampled. Throws
  // std::invalid_argument (the state kept) for an empty or non-finite frame, depths of another
  // size, a frame larger than the output, or a bad camera.
  const Image& add(const Image& frame, const Camera& camera, const PixelDepths& depths, int out_width,
                   int out_height, const glm::dvec3& cloud_shift_m = glm::dvec3(0.0));
  // Forget the history: the next frame starts again (a sun jump, new clouds).
  void reset();
  // Frames accumulated since the last reset (1 after the first).
  unsigned frames() const { return frames_; }
  const Image& output() const { return output_; }

 private:
  TemporalSettings settings_;
  Camera camera_;                // the output's camera (no offset), the history's view
  Image output_;                 // the history: the last output
  std::vector<float> weight_;    // per output pixel, the history's weight in samples
  unsigned frames_ = 0;
};

}  // namespace nimbus::render
