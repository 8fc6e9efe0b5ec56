// Validation of the homogeneous medium's coefficients: one message per bad field.
#include "nimbus/render/media/medium.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace nimbus::render {

void validate(const Medium& medium) {
  const double sigma_t = medium.extinction_per_m;
  if (!std::isfinite(sigma_t) || sigma_t < 0.0)
    throw std::invalid_argument("medium extinction_per_m must be finite and >= 0 (got " + std::to_string(sigma_t) + ")");
  const double albedo = medium.albedo;
  if (!(albedo >= 0.0 && albedo <= 1.0))
    throw std::invalid_argument("medium albedo must be in [0, 1] (got " + std::to_string(albedo) + ")");
  const Phase& p = medium.phase;
  if (phase_takes_g(p.kind) && !(p.g > -1.0 && p.g < 1.0))
    throw std::invalid_argument("medium phase g must be in (-1, 1) (got " + std::to_string(p.g) + ")");
}

}  // namespace nimbus::render
