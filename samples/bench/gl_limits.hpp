// What the GL device does per second for the work a frame is made of, measured on bare passes at a
// frame's size: fragments shaded (a full-screen pass writing RGBA32F, the slicer's target format),
// fragments blended (the same under the slices' "over" blend), trilinear samples of a 3D R16F
// texture (the clouds' density format), RGBA32F pixels read back, and the slicer's round trip between
// its two targets with almost no fragments. `nimbus bench gl` prints
// them; `nimbus bench view` measures them in the same run and gives each pass's time as a
// multiple of what its fragments would take at the limit. Needs a current GL 4.5 context.
#pragma once
#include <string>

namespace nimbus::cli {

struct GlLimits {
  int width = 0, height = 0;
  double fragments_per_s = 0;        // a shaded fragment written (RGBA32F, no blend)
  double blended_per_s = 0;          // the same blended over what is there
  double samples_3d_per_s = 0;       // trilinear 3D-texture samples, beyond the fragment's own cost
  double readback_pixels_per_s = 0;  // RGBA32F pixels through glReadPixels
  double slice_round_trips_per_s = 0;  // a slice's two passes with ~no fragments, each reading the other's target
  std::string device;                // GL_RENDERER
};

// Each rate the best of `repeats` timed runs (glFinish around each).
GlLimits measure_gl_limits(int width, int height, int repeats = 3);

// The table `nimbus bench gl` prints: its header, and one row per size.
void print_gl_limits_header();
void print_gl_limits_row(const GlLimits& limits);

}  // namespace nimbus::cli
