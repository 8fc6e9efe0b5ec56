// Ebert's gas function.
#include "nimbus/volume/gas.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace nimbus::volume {

float gas_density(float turb, const GasParams& g) {
  if (!(turb > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (g.sine) turb = 0.5f * (1.0f + std::sin(turb * std::numbers::pi_v<float>));
  const float d = std::pow(turb * g.max_density, g.exponent);
  // An overflow saturates rather than vanish (a voxel dropped as 0 would hollow the cloud out);
  // CloudModel refuses parameters whose densities could reach it.
  return std::isfinite(d) ? d : std::numeric_limits<float>::max();
}

}  // namespace nimbus::volume
