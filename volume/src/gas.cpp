// Ebert's gas function.
#include "nimbus/volume/gas.hpp"

#include <cmath>
#include <numbers>

namespace nimbus::volume {

float gas_density(float turb, const GasParams& g) {
  if (!(turb > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (g.sine) turb = 0.5f * (1.0f + std::sin(turb * std::numbers::pi_v<float>));
  const float d = std::pow(turb * g.max_density, g.exponent);
  return std::isfinite(d) ? d : 0.0f;
}

}  // namespace nimbus::volume
