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
// infinite, or the albedo is outside [0, 1].
void validate(const Medium& medium);

}  // namespace nimbus::render
