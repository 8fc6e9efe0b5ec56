// The sun, its colour and its ambient light, set up once for every program (sun_setup.hpp).
#include "nimbus/render/scene/sun_setup.hpp"

#include <cmath>
#include <stdexcept>

#include "nimbus/render/scene/daylight.hpp"

namespace nimbus::render {

SunSetup set_up_sun(const Scene* scene, const glm::dvec3& direction_to_sun, SunColour colour) {
  const double len = glm::length(direction_to_sun);
  if (!(std::isfinite(len) && len > 0.0)) throw std::invalid_argument("sun direction must be finite and non-zero");
  const bool physical = scene && scene->sky && scene->sky->atmosphere;
  SunSetup s;
  if (physical || colour == SunColour::Daylight) {
    const double altitude_m = physical ? scene->sky->atmosphere->view.altitude_m : kDaylightViewerAltitudeM;
    const Daylight d = daylight(direction_to_sun, altitude_m);
    s.sun = sun_light(direction_to_sun, d.cloud_sun_irradiance_w_m2);  // as given: normalised on use
    if (physical) s.sky = d.sky;
    s.ambient_w_sr_m2 = d.ambient_w_sr_m2;
    return s;
  }
  if (scene && scene->sun) s.sun = *scene->sun;  // its irradiance stays; else the default sun's
  s.sun.direction_to_sun = direction_to_sun;
  if (scene) s.ambient_w_sr_m2 = sky_ambient(*scene);
  return s;
}

std::optional<glm::dvec3> sky_ambient(const Scene& scene) {
  if (!scene.sky) return std::nullopt;
  return sky_mean_radiance(*scene.sky);
}

void place_sun(Scene& scene, const SunSetup& setup) {
  scene.sun = setup.sun;
  if (setup.sky) scene.sky = setup.sky;
}

}  // namespace nimbus::render
