// Adaptive quality steps (adaptive_quality.hpp).
#include "adaptive_quality.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus::viewer {

void AdaptiveQuality::update(bool moving, double frame_ms, double now_s) {
  if (moving) {
    last_motion_s = now_s;
    // A frame costs about pixels x slices: predict each level from this frame and take the best
    // one that fits the budget (the cheapest when none does).
    auto cost = [this](int l) {
      const QualityLevel& q = level_values(l);
      return q.render_scale * q.render_scale * (0.5 + 0.5 * q.slice_share);
    };
    const double now_cost = cost(level_);
    int best = kQualityLevelCount - 1;
    for (int l = 0; l < kQualityLevelCount; ++l) {
      if (frame_ms * cost(l) / now_cost <= budget_ms) {
        best = l;
        break;
      }
    }
    level_ = best;
  } else if (now_s - last_motion_s >= settle_s) {
    level_ = 0;
  }
}

render::FrameQuality level_quality(const QualityLevel& q, int full_slices, int full_light_res) {
  render::FrameQuality f;
  f.render_scale = q.render_scale;
  f.slices = std::max(8, static_cast<int>(std::lround(full_slices * q.slice_share)));
  if (q.light_share < 1.0) f.light_res = std::max(16, static_cast<int>(std::lround(full_light_res * q.light_share)));
  return f;
}

render::FrameQuality AdaptiveQuality::quality(int full_slices, int full_light_res) const {
  return level_quality(level_values(level()), full_slices, full_light_res);
}

}  // namespace nimbus::viewer
