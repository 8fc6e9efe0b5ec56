// The C++ side of the one contract between the renderer and its shaders (shaders/lib/contract.glsl):
// the file itself compiled as C++ into namespace nimbus::render::contract. Each enum maps its
// values to these codes in its own file, with one switch (phase_code in phase.cpp, jitter_code and
// shaft_method_code in shaft_method.cpp, airlight_eval_code in airlight_parse.cpp), so a value added
// to an enum and not mapped stops the build (-Werror=switch); tests/cpu/test_contract_codes.cpp and
// tests/gl/test_contract.cpp check that each code selects its own function.
#pragma once

namespace nimbus::render::contract {
#include "lib/contract.glsl"
}  // namespace nimbus::render::contract
