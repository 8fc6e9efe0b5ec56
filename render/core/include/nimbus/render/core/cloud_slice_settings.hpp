// The half-angle slicer's settings (cloud_renderer.hpp): slice count, light buffer, jitter,
// forward-scattering blur, multiple-scattering octaves, the compositing branch and how many
// lights get a pass.
#pragma once
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

struct CloudSliceSettings {
  int slices = 128;        // planes across the clouds' extent along the slicing axis, [2, 4096]
  int light_res = 256;     // light buffer side, texels, [16, 4096]
  bool jitter = true;      // blue-noise offset of each pixel's sample within its slab (no banding)
  unsigned frame = 0;      // varies the jitter from frame to frame
  bool ambient = true;     // add each cloud's optics.ambient_radiance
  // Kniss forward-scattering blur: the light buffer is spread by a cone of this half-angle as it
  // propagates (radius grows with depth). 0 switches it off.
  double blur_cone_rad = 0.0;
  MultipleScattering multiple;  // octaves = 0: single scattering
  // Which compositing branch: Auto chooses by the angle between the view and light directions
  // (the half-angle rule); the others force one, for tests at the switch.
  enum class Branch { Auto, FrontToBack, BackToFront } branch = Branch::Auto;
  // Lights drawn, one slicing pass (and light buffer) each: the strongest at the clouds' centre
  // (strongest_lights, light.hpp); the rest are left out and named in the metadata. [1, 8]
  int max_lights = 4;
  // A periodic cloud (CloudVolume::period_m) is drawn with copies of its tile out to this
  // distance from the eye, metres, so that a field fills the sky to the horizon (cloud_tiles.hpp);
  // 0: one tile. [0, kMaxRepeatToM]
  double repeat_to_m = 0.0;
};

// The farthest a periodic field is repeated, metres: --repeat-to and a view state's
// renderer.repeat_to (the copies each way are bounded too: kMaxRepeatsPerAxis, cloud_tiles.hpp).
inline constexpr double kMaxRepeatToM = 1e6;

void validate(const CloudSliceSettings& settings);

// The "slices" metadata key: every setting above.
void describe_slices(Image& image, const CloudSliceSettings& settings);

}  // namespace nimbus::render
