// One light (render/core/light.hpp's Light) as every shader reads it: the members of LightsBlock
// (lib/light_list.glsl: the scene's lamps and sun) and of SliceLightBlock (lib/cloud_light_block.glsl:
// the slicer pass's light). Common subset of GLSL and C++: render/core/light_record.hpp includes
// it, and render::light_record packs a Light into it. lib/light_eval.glsl evaluates it.
#ifndef NIMBUS_LIGHT_RECORD_GLSL
#define NIMBUS_LIGHT_RECORD_GLSL
#include "lib/contract.glsl"

struct LightRecord {
  vec4 position;  // xyz: a lamp's position (metres), or the unit direction towards the sun; w: LIGHT_LAMP or LIGHT_SUN
  vec4 power;     // rgb: a lamp's intensity (W/sr) or the sun's irradiance (W m^-2); w: a lamp's min distance (metres)
  vec4 spot;      // xyz: a spot's unit axis (propagation); w: 1 for a spot, 0 otherwise
  vec4 spot_cos;  // a spot: x = cos(outer), y = cos(inner)
};

#endif
