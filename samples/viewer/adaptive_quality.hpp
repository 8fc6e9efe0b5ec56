// The viewer's adaptive quality: while the camera or the sun moves, lower the render scale and
// the slice count to the best level whose predicted cost (this frame's time scaled by pixels and,
// half-weighted, slices) fits the budget; when everything has been still for a moment, draw at
// full quality again. `nimbus bench view` measures what each step
// costs in error against the full-quality frame.
#pragma once
#include "nimbus/render/frame/sky_renderer.hpp"

namespace nimbus::viewer {

struct QualityLevel {
  double render_scale;       // times the state's
  double slice_share;        // of the state's slices
  double light_share = 1.0;  // of the state's light buffer side
};
// Level 0 is full quality; each next one is cheaper.
inline constexpr QualityLevel kQualityLevels[] = {{1.0, 1.0}, {0.75, 0.75}, {0.5, 0.5}, {0.5, 0.34}, {0.35, 0.25}, {0.25, 0.2}};
// The same number of levels for accumulated frames (ViewerOptions::temporal): the accumulation
// recovers the pixels a smaller frame drops, not the slices, so the pixels go first.
// The lowest two also halve the light buffer's side: its pass does not shrink with the pixels, and
// was 40 % of the GPU time of the lowest level's frame (docs/viewer.md).
inline constexpr QualityLevel kTemporalQualityLevels[] = {{1.0, 1.0},       {0.75, 1.0},      {0.5, 1.0},
                                                          {0.5, 0.75},      {0.35, 0.6, 0.5}, {0.25, 0.5, 0.5}};
inline constexpr int kQualityLevelCount = sizeof(kQualityLevels) / sizeof(kQualityLevels[0]);
static_assert(sizeof(kTemporalQualityLevels) == sizeof(kQualityLevels));

// A level's frame quality for a state of full_slices slices and a full_light_res light buffer.
render::FrameQuality level_quality(const QualityLevel& level, int full_slices, int full_light_res);

class AdaptiveQuality {
 public:
  double budget_ms = 100.0;  // per frame while moving
  double settle_s = 0.3;     // still this long (real time) before full quality returns
  bool enabled = true;
  bool temporal = false;     // the levels of kTemporalQualityLevels

  // After a frame: whether the camera or sun moved for it, what it cost, and the real time now.
  void update(bool moving, double frame_ms, double now_s);
  int level() const { return enabled ? level_ : 0; }
  render::FrameQuality quality(int full_slices, int full_light_res) const;
  const QualityLevel& level_values(int level) const { return (temporal ? kTemporalQualityLevels : kQualityLevels)[level]; }

 private:
  int level_ = 0;
  double last_motion_s = -1e9;
};

}  // namespace nimbus::viewer
