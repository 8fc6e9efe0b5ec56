// The sun of a frame, its colour and the ambient light it brings, set up in one place for
// `nimbus render --sun`, the viewer's clock (SkyRenderer) and the frame pipeline (FrameRenderer::
// set_sun): a scene under the physical sky takes the daylight for the sun's direction (daylight.hpp,
// Hillaire 2020): the sun at the cloud layer, the sky that goes with it and that sky's mean radiance
// on the clouds. Elsewhere the scene's own sun moves and keeps its irradiance, unless the daylight
// is asked for everywhere (the viewer's time of day lights every scene by it).
#pragma once
#include <optional>

#include <glm/glm.hpp>

#include "nimbus/render/core/light.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

// Where the sun's colour comes from.
enum class SunColour {
  Scene,     // the daylight where the scene has the physical sky; else the scene's sun's own
             // irradiance (the default sun's when it has none, or with no scene)
  Daylight,  // the daylight for every scene and for clouds alone (the viewer's clock)
};

struct SunSetup {
  Light sun;                                  // LightKind::Sun; the scene's sun and the clouds'
  std::optional<Sky> sky;                     // set: the physical sky for this sun (the scene's becomes it)
  std::optional<glm::dvec3> ambient_w_sr_m2;  // the sky's light on the clouds; none: no sky (the caller's stands)
};

// The sun arriving from `direction_to_sun` over `scene` (nullptr: clouds alone). The daylight is
// seen from the physical sky's own altitude, or from kDaylightViewerAltitudeM without one. The
// sun's direction is kept as given (every light's is normalised on use). Throws std::invalid_argument for a zero or
// non-finite direction, or (with the daylight) a sun more than 10 degrees below the horizon.
SunSetup set_up_sun(const Scene* scene, const glm::dvec3& direction_to_sun, SunColour colour);

// The ambient light of a scene's own sky on the clouds (its mean radiance), or none without a sky.
std::optional<glm::dvec3> sky_ambient(const Scene& scene);

// The scene's sun becomes the setup's, and its sky the setup's physical sky when there is one.
void place_sun(Scene& scene, const SunSetup& setup);

}  // namespace nimbus::render
