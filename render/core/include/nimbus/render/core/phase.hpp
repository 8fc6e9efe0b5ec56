// Phase functions of the medium (thesis eqs. 13-17), normalised over the sphere: the fraction
// of scattered light per steradian as a function of the scattering angle theta between the
// light's propagation direction and the scattered direction (theta = 0 is forward).
#pragma once
#include <string>

namespace nimbus::render {

enum class PhaseKind { Isotropic, HenyeyGreenstein, Schlick, Rayleigh };

struct Phase {
  PhaseKind kind = PhaseKind::Isotropic;
  double g = 0.0;  // asymmetry in (-1, 1) for Henyey-Greenstein and Schlick; unused otherwise
};

// Whether the kind has an asymmetry g (which must then be in (-1, 1)).
bool phase_takes_g(PhaseKind kind);

// The kind's PHASE_* code in shaders/lib/contract.glsl (what the shaders' phase_value takes).
int phase_code(PhaseKind kind);

// p(theta) given cos(theta), per steradian. Double precision reference.
double phase_value(const Phase& phase, double cos_theta);

// Schlick's k from g (thesis eq. 16): k = 1.55 g - 0.55 g^3.
double schlick_k(double g);

// "isotropic", "hg:G", "schlick:G", "rayleigh" <-> Phase. Parsing throws
// std::invalid_argument naming the text when it is malformed or g is outside (-1, 1).
Phase parse_phase(const std::string& text);
std::string to_string(const Phase& phase);

}  // namespace nimbus::render
