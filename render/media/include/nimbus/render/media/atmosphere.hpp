// The Earth's clear atmosphere as Hillaire (2020) models it: a spherical shell of air
// (Rayleigh scattering), aerosols (Mie scattering with a Cornette-Shanks phase, some absorption)
// and ozone (absorption only, in a tent-shaped layer), each with its density profile over
// altitude. The shared maths of the sky's tables (atmosphere_tables.hpp) and its brute-force
// reference (render/reference/atmosphere_reference.hpp): media, phase functions and the
// geometry of rays in the shell, in double precision. Lengths in metres.
#pragma once
#include <glm/glm.hpp>

namespace nimbus::render {

struct Atmosphere {
  double bottom_radius_m = 6360.0e3;  // the ground
  double top_radius_m = 6460.0e3;     // where the air ends
  // Rayleigh: scattering at sea level per channel (R, G, B), density exp(-h / H)
  glm::dvec3 rayleigh_scattering_per_m{5.802e-6, 13.558e-6, 33.1e-6};
  double rayleigh_scale_height_m = 8000.0;
  // Mie (aerosols): grey, density exp(-h / H), Cornette-Shanks phase with asymmetry g
  double mie_scattering_per_m = 3.996e-6;
  double mie_extinction_per_m = 4.440e-6;
  double mie_scale_height_m = 1200.0;
  double mie_g = 0.8;
  // Ozone: absorption at the peak, density max(0, 1 - |h - centre| / half width)
  glm::dvec3 ozone_absorption_per_m{0.650e-6, 1.881e-6, 0.085e-6};
  double ozone_centre_m = 25000.0;
  double ozone_half_width_m = 15000.0;
  double ground_albedo = 0.3;  // Lambertian, grey
  // Solar irradiance above the atmosphere, W m^-2 per channel; chosen so that the sun 33 degrees
  // up reaches the ground as the sky scene's sun did, 6 x (1, 0.95, 0.88), within 1 %.
  glm::dvec3 solar_irradiance_w_m2{6.7, 7.4, 8.7};
  double sun_angular_radius_rad = 0.004675;

  bool operator==(const Atmosphere&) const = default;
};

// Throws std::invalid_argument naming the field (non-finite, negative, top not above bottom, ...).
void validate(const Atmosphere& a);

// Scattering and extinction coefficients at an altitude, per metre.
struct AtmosphereMedium {
  glm::dvec3 rayleigh_scattering{0.0};
  double mie_scattering = 0.0;
  glm::dvec3 scattering{0.0};  // Rayleigh + Mie
  glm::dvec3 extinction{0.0};  // scattering + Mie absorption + ozone
};
AtmosphereMedium atmosphere_medium(const Atmosphere& a, double altitude_m);

// Phase functions per steradian of the cosine between propagation directions:
// Rayleigh 3 (1 + mu^2) / (16 pi); Cornette & Shanks (1992)
// 3 (1 - g^2) (1 + mu^2) / (8 pi (2 + g^2) (1 + g^2 - 2 g mu)^{3/2}).
double rayleigh_phase(double mu);
double cornette_shanks_phase(double g, double mu);

// Geometry of a ray that starts at altitude h with cos mu of its zenith angle.
// Cosine of the horizon's zenith angle seen from h: -sqrt(h (2R + h)) / (R + h).
double horizon_cos(const Atmosphere& a, double altitude_m);
bool ray_hits_ground(const Atmosphere& a, double altitude_m, double mu);
// Distance to the top of the atmosphere (from inside), or to the ground; stable forms.
double distance_to_top(const Atmosphere& a, double altitude_m, double mu);
double distance_to_ground(const Atmosphere& a, double altitude_m, double mu);  // only where ray_hits_ground
// Distance to where the ray leaves the air: the ground if it meets it, else the top.
double distance_to_exit(const Atmosphere& a, double altitude_m, double mu);
// Where the ray is after distance t: its altitude, and the cosines of the zenith angles of the
// ray and of the sun there (nu = cos of the angle between the ray and the sun).
struct ShellPoint {
  double altitude_m;
  double mu;
  double mu_s;
};
ShellPoint shell_point(const Atmosphere& a, double altitude_m, double mu, double mu_s, double nu, double t_m);

// The energy-conserving step weight per channel (Hillaire 2015): int_0^dt e^{-sigma s} ds =
// (1 - e^{-sigma dt}) / sigma, by its series where sigma dt is tiny.
glm::dvec3 step_weight(const glm::dvec3& sigma, double dt);

// Direction i of n spread over the sphere with equal areas (the Fibonacci sphere), y up.
glm::dvec3 fibonacci_sphere(int i, int n);

// The share of the sun's disc above the horizon seen from h (a linear ramp across the disc).
double sun_visibility(const Atmosphere& a, double altitude_m, double mu_s);

}  // namespace nimbus::render
