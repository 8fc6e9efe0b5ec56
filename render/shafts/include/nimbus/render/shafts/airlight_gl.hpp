// The airlight evaluations of airlight.hpp run through the shaders' own GLSL functions on an
// OpenGL 4.5 context (shaders/airlight_eval.comp.glsl), so the GPU path's error is measured
// against the same double-precision reference as the CPU one.
#pragma once
#include <vector>

#include "nimbus/render/core/airlight.hpp"

namespace nimbus::render {

// evaluate_airlight through the GLSL functions: a headless context is created for the call. Quadrature has no GL form (std::invalid_argument);
// throws GlUnavailable when no context can be made.
std::vector<double> evaluate_airlight_gl(const std::vector<AirlightQuery>& queries, const AirlightMethod& method,
                                         const Phase& phase = {});

}  // namespace nimbus::render
