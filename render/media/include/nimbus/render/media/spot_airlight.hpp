// The single-scattered airlight of a spot (a lamp narrowed to a cone, light.hpp) over a segment
// of a view ray, per unit intensity:
//   A = int_x0^x1 sigma_s p(theta) w(u) e^(-sigma_t (x + d)) / d^2 dx
// (Sun et al. 2005 eq. 5 with the spot's weight w; derivation in shaders/lib/spot_airlight.glsl).
// Sun's closed form holds for lamps that shine every way; for a spot the shaders integrate
// numerically, and this header gives that float path on the CPU and its double reference.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/light.hpp"
#include "nimbus/render/core/phase.hpp"

namespace nimbus::render {

struct SpotSegmentQuery {
  double sigma_t = 0.0, sigma_s = 0.0;             // extinction and scattering, per metre
  Light lamp;                                      // its position and cone (no cone: w = 1)
  glm::dvec3 origin_m{0.0};                        // the ray's origin
  glm::dvec3 dir{0.0, 0.0, -1.0};                  // the ray's direction, unit
  double x0 = 0.0, x1 = 1.0;                       // metres along the ray, 0 <= x0 <= x1 (x1 may be +inf)
  Phase phase;
};

// Throws std::invalid_argument naming the field (non-finite or negative coefficients, a
// direction that is not unit, x1 < x0, an invalid lamp).
void validate(const SpotSegmentQuery& q);

// Where the ray origin + x dir crosses the spot's inner and outer cones, x >= 0 ascending;
// none for a lamp without a cone or a ray through the lamp. Cuts for quadratures.
std::vector<double> spot_cone_crossings(const Light& lamp, const glm::dvec3& origin_m, const glm::dvec3& dir);

// Double-precision reference: adaptive Gauss-Kronrod in the angle psi (x = c + h tan psi),
// split at the cone crossings, relative tolerance 1e-10.
double spot_segment_airlight_reference(const SpotSegmentQuery& q);

// The shaders' float path (shaders/lib/spot_airlight.glsl compiled as C++): SPOT_AL_NODES
// midpoint nodes over the part of the ray inside the outer cone.
double spot_segment_airlight_float(const SpotSegmentQuery& q);

}  // namespace nimbus::render
