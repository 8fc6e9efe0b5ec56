// Ebert's gas density function (Ebert et al. 2003, as in Hoffmann 2007, slide "Gasmodellierung"):
//   density = pow(turb * max_density, exponent)
// and its sine variant, which first maps turb to (1 + sin(turb * pi)) / 2. The slide prints
// that as "(1 + sin(turbulence(pt)*PI)/2)", whose range [0.5, 1.5] cannot be intended; the
// parenthesised form keeps [0, 1].
#pragma once

namespace nimbus::volume {

struct GasParams {
  float max_density = 1.0f;  // scales the field before the power (densities above 1 allowed)
  float exponent = 1.0f;     // > 0: above 1 sharpens the edges, below 1 softens them
  bool sine = false;         // apply the sine variant first
};

// turb <= 0 gives 0 (never NaN); the result is finite and >= 0 for finite input: an overflow
// saturates at the largest float, never 0.
float gas_density(float turb, const GasParams& g);

}  // namespace nimbus::volume
