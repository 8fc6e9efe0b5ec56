// The homogeneous participating medium (fog) that fills the light-shaft scene.
#pragma once
#include "nimbus/render/core/phase.hpp"

namespace nimbus::render {

struct Medium {
  double extinction_per_m = 0.04;  // sigma_t, per metre (Sun et al.'s beta when albedo = 1)
  double albedo = 1.0;             // sigma_s / sigma_t, in [0, 1]
  Phase phase;

  double scattering_per_m() const { return albedo * extinction_per_m; }
};

// Throws std::invalid_argument naming the field when a coefficient is negative, NaN or
// infinite, the albedo is outside [0, 1], or the phase is not one lobe.
void validate(const Medium& medium);

// parse_phase for the fog: one lobe, "isotropic", "hg:G", "schlick:G" or "rayleigh";
// std::invalid_argument naming the text for those malformed and for a dual lobe (a cloud's).
Phase parse_medium_phase(const std::string& text);

}  // namespace nimbus::render
