// The C++ side of the one contract between the renderer and its shaders (shaders/lib/contract.glsl):
// the file itself compiled as C++ into namespace nimbus::render::contract, and the explicit maps
// from nimbus's enums to its codes. A switch per enum, so a value added to an enum and not mapped
// here stops the build (-Werror=switch); tests/gl/test_contract.cpp checks the codes on the GPU.
#pragma once
#include "nimbus/render/core/airlight.hpp"
#include "nimbus/render/core/phase.hpp"
#include "nimbus/render/core/shaft_method.hpp"

namespace nimbus::render {

namespace contract {
#include "lib/contract.glsl"
}  // namespace contract

// PHASE_* of the phase kind.
int phase_code(PhaseKind kind);
// JITTER_* of the jitter.
int jitter_code(Jitter jitter);
// SHAFT_METHOD_* of a GPU shaft method; std::invalid_argument for Reference (no shader runs it).
int shaft_method_code(ShaftMethod::Kind kind);
// AIRLIGHT_EVAL_* of an airlight method; std::invalid_argument for Quadrature (CPU only).
int airlight_eval_code(AirlightMethod::Kind kind);

}  // namespace nimbus::render
