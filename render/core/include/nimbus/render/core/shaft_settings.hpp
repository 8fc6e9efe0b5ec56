// The light-shaft renderer's settings (render/shafts shaft_renderer.hpp): its shadow maps'
// sizes, the ground's extent, the ray march's cutoff, the shadow-volume skirts, the jitter, and
// whether surfaces add the airlight they reflect. Plain data, so that the frame description
// (render/frame frame_settings.hpp) and the programs' settings hold it without the GL layer.
#pragma once
#include <cstddef>

namespace nimbus::render {

struct ShaftSettings {
  int point_shadow_res = 1024;    // texels per cube face side
  int sun_shadow_res = 2048;      // texels per side of the sun's orthographic map
  double ground_extent_m = 1000;  // half-size of the ground quad standing for the infinite plane (under a sky: at least 3x its distance)
  double march_cutoff_optical = 9.21;  // rays hitting nothing are marched to this optical depth (e^-9.21 = 1e-4)
  double silhouette_jump = 0.02;  // relative distance jump between texels that makes a shadow-volume skirt
  std::size_t max_skirt_quads = 1u << 19;  // per light; beyond it the whole ray is sampled
  unsigned jitter_seed = 1;
  // Surfaces add the airlight they reflect from each point light (Sun et al. eq. 13's L_p,a,
  // core/surface_airlight.hpp); the sun adds none. The reference's switch is ReferenceSettings'.
  bool surface_airlight = true;

  bool operator==(const ShaftSettings&) const = default;
};

}  // namespace nimbus::render
