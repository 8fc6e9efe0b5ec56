// The half-angle slicer's settings (cloud_renderer.hpp): slice count, light buffer, jitter,
// forward-scattering blur, multiple-scattering octaves, the compositing branch and how many
// lights get a pass.
#pragma once
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::render {

struct CloudSliceSettings {
  // The ranges of these settings, and the defaults of those a front end sets, are the table's
  // (render_settings.hpp).
  int slices = int(setting(Setting::Slices).still_default);        // planes across the clouds' extent along the slicing axis
  int light_res = int(setting(Setting::LightRes).still_default);   // light buffer side, texels
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
  // (strongest_lights, light.hpp); the rest are left out and named in the metadata.
  int max_lights = int(setting(Setting::MaxLights).still_default);
  // A periodic cloud (CloudVolume::period_m) is drawn with copies of its tile out to this
  // distance from the eye, metres, so that a field fills the sky to the horizon (cloud_tiles.hpp);
  // 0: one tile, the library's default (a front end's "auto" is the table's: 32 km under the sky).
  double repeat_to_m = 0.0;
};

// The farthest a periodic field is repeated, metres: --repeat-to and a view state's
// renderer.repeat_to (the copies each way are bounded too: kMaxRepeatsPerAxis, cloud_tiles.hpp).
inline constexpr double kMaxRepeatToM = setting(Setting::RepeatTo).max;

void validate(const CloudSliceSettings& settings);

// The "slices" metadata key: every setting above.
void describe_slices(Image& image, const CloudSliceSettings& settings);

}  // namespace nimbus::render
