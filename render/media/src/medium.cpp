// Validation of the homogeneous medium's coefficients: one message per bad field.
#include "nimbus/render/media/medium.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/base/input_limits.hpp"

namespace nimbus::render {

void validate(const Medium& medium) {
  const double sigma_t = medium.extinction_per_m;
  if (!std::isfinite(sigma_t) || sigma_t < 0.0)
    throw std::invalid_argument("medium extinction_per_m must be finite and >= 0 (got " + std::to_string(sigma_t) + ")");
  const double albedo = medium.albedo;
  if (!(albedo >= 0.0 && albedo <= 1.0))
    throw std::invalid_argument("medium albedo must be in [0, 1] (got " + std::to_string(albedo) + ")");
  validate(medium.phase, "medium phase");
  if (medium.phase.kind == PhaseKind::DualHenyeyGreenstein)  // the fog's shaders and tables take one lobe
    throw std::invalid_argument("medium phase " + to_string(medium.phase) +
                                ": the fog takes one lobe (isotropic, hg:G, schlick:G or rayleigh); two are a cloud's");
}

Phase parse_medium_phase(const std::string& text) {
  const Phase p = parse_phase(text);
  if (p.kind == PhaseKind::DualHenyeyGreenstein)
    throw std::invalid_argument("phase '" + echo(text) +
                                "': the fog takes one lobe (isotropic, hg:G, schlick:G or rayleigh); two are a cloud's");
  return p;
}

}  // namespace nimbus::render
