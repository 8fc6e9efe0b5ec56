// `nimbus bench view`'s paths: the viewer driven headless along a scripted orbit, a time-lapse
// or a sun drag, with each frame's time, its error against the full-quality frame, the adaptive
// quality's levels, the keyframes and light volumes made, and the GPU time per pass.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "viewer/viewer.hpp"

namespace nimbus::cli {

struct PathResult {
  std::vector<double> ms, errors;
  std::map<int, int> levels;
  int held = 0;                   // frames whose evolution waited for its keyframes
  int64_t keyframes = 0;          // made during the path
  double keyframe_s = 0.0;        // generation time of those
  double longest_generating = 0;  // the longest frame while a keyframe was being made
  int stale = 0, stand_in = 0;    // frames drawn with an earlier light volume / the octaves standing in
  int64_t volumes = 0;            // light volumes made during the path
  double volume_s = 0.0;          // their build time
  // GPU time per pass, per frame (timer queries where the driver has them: FrameStats), ms, and
  // fragment shader invocations (< 0: not counted).
  std::map<std::string, std::vector<double>> pass_ms, pass_fragments;
  std::string timing;             // how the GPU times were taken
  int preview = 0;                // frames drawn with the new sun's quick volume
  // The sun drag: per drag, real ms from its last step to the first frame lit by a volume of the
  // new sun (its preview or its full volume) and to the first with its full volume.
  std::vector<double> sun_first_ms, sun_full_ms;
  std::vector<double> temporal_ms;  // the accumulation's CPU time per frame (temporal paths)
};

// The passes of a frame whose GPU time bench view reports, in drawing order.
extern const char* const kPasses[8];

enum class Path { Orbit, TimeLapse, SunDrag };

// The sun drag: time held still; every kDragCycle frames the sun's azimuth is dragged kDragSteps
// frames at kDragStepDeg a frame (the panel's slider), then held.
constexpr int kDragCycle = 24, kDragSteps = 6;
constexpr double kDragStepDeg = 3.0;

// The q-quantile of `v` (linear between ranks); 0 for none.
double percentile(std::vector<double> v, double q);

// `frames` frames of `path` at w x h, the adaptive quality on or off; every `error_every`-th
// frame (0: none) also compared with the full-quality frame of the same state.
PathResult run_path(viewer::Viewer& v, Path path, int w, int h, int frames, bool adaptive, int error_every);

}  // namespace nimbus::cli
