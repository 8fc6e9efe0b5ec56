// Phase functions (thesis eqs. 13-17), normalised over the sphere: the fraction of scattered
// light per steradian as a function of the scattering angle theta between the light's
// propagation direction and the scattered direction (theta = 0 is forward). One type for the fog
// and the clouds alike: the fog takes one lobe of any kind, clouds a sum of Henyey-Greenstein
// lobes (as_dual_lobes).
#pragma once
#include <string>

namespace nimbus::render {

// The fog's kinds (one lobe, each with a PHASE_* shader code) come first: tests enumerate them up
// to the first that phase_code refuses. DualHenyeyGreenstein: p = w HG(theta; g) + (1 - w)
// HG(theta; g_back), the clouds' forward lobe with some backward scattering.
enum class PhaseKind { Isotropic, HenyeyGreenstein, Schlick, Rayleigh, DualHenyeyGreenstein };

struct Phase {
  PhaseKind kind = PhaseKind::Isotropic;
  // Asymmetry in (-1, 1) for Henyey-Greenstein and Schlick, and a dual lobe's first (forward)
  // lobe; unused otherwise.
  double g = 0.0;
  double g_back = 0.0;          // DualHenyeyGreenstein: the second lobe's asymmetry, (-1, 1)
  double forward_weight = 1.0;  // DualHenyeyGreenstein: the first lobe's weight w, [0, 1]
  bool operator==(const Phase&) const = default;
};

// w HG(g_forward) + (1 - w) HG(g_back).
constexpr Phase dual_lobe_phase(double g_forward, double g_back, double forward_weight) {
  return {PhaseKind::DualHenyeyGreenstein, g_forward, g_back, forward_weight};
}

// A sum of Henyey-Greenstein lobes (isotropic, hg:G or dual) as its dual-lobe form, which is what
// the clouds' methods take (isotropic is dual(0, 0, 1), hg:G is dual(G, 0, 1)); the same function
// of theta. Throws std::invalid_argument naming the phase for Schlick and Rayleigh.
Phase as_dual_lobes(const Phase& phase);

// Whether the kind has an asymmetry g (which must then be in (-1, 1)).
bool phase_takes_g(PhaseKind kind);

// Throws std::invalid_argument, "<what> g must be in (-1, 1) (got 1)", when an asymmetry the kind uses is outside (-1, 1)
// (or not finite) or a dual lobe's weight is outside [0, 1].
void validate(const Phase& phase, const std::string& what);

// The kind's PHASE_* code in shaders/lib/contract.glsl (what the fog's shaders' phase_value takes:
// one lobe; a dual lobe has none and throws std::invalid_argument).
int phase_code(PhaseKind kind);

// p(theta) given cos(theta), per steradian. Double precision reference.
double phase_value(const Phase& phase, double cos_theta);

// Schlick's k from g (thesis eq. 16): k = 1.55 g - 0.55 g^3.
double schlick_k(double g);

// "isotropic", "hg:G", "schlick:G", "rayleigh", "dual:GF,GB,W" <-> Phase. Parsing throws
// std::invalid_argument naming the text when it is malformed or a number is out of its range.
Phase parse_phase(const std::string& text);
std::string to_string(const Phase& phase);

}  // namespace nimbus::render
