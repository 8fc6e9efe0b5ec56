// The physical sky's model (render/media/atmosphere.hpp, Hillaire 2020) integrated by brute force
// in double precision, with no table: the reference that every table in atmosphere_tables.hpp
// and the sky's radiance are checked against. Slow (tens of milliseconds to seconds a query).
//   - Transmittance: the optical depth by adaptive Gauss-Kronrod quadrature.
//   - Psi_ms: the same second-order integral as the table (Hillaire section 5.5), over 512
//     directions with 128 steps each, the sun's transmittance integrated at every step.
//   - Sky radiance and aerial perspective: 2000 steps along the view ray, the sun's
//     transmittance integrated at each, and Psi_ms evaluated exactly at 24 points along the ray
//     and interpolated between them (it varies slowly).
#pragma once
#include <glm/glm.hpp>

#include "nimbus/render/media/atmosphere.hpp"

namespace nimbus::render {

// Transmittance from (altitude, mu) to the top of the atmosphere (0 where the ray meets the ground).
glm::dvec3 reference_transmittance(const Atmosphere& a, double altitude_m, double mu);
// Psi_ms per unit solar irradiance, sr^-1.
glm::dvec3 reference_multiple_scattering(const Atmosphere& a, double altitude_m, double mu_s);

struct AtmosphereRay {
  double altitude_m = 2.0;
  glm::dvec3 direction_to_sun{0.0, 1.0, 0.0};  // y up
  glm::dvec3 direction{0.0, 1.0, 0.0};         // the view ray's, y up
  double max_distance_m = 1.0e30;              // where the ray stops, if before the ground or the top
};
struct AtmosphereRadiance {
  glm::dvec3 inscattered_w_sr_m2{0.0};  // sun light scattered toward the viewer (every order), plus the
                                        // sunlit ground's where the ray ends on it
  glm::dvec3 transmittance{1.0};
};
AtmosphereRadiance reference_sky(const Atmosphere& a, const AtmosphereRay& ray);

}  // namespace nimbus::render
