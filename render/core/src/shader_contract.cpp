// Enum-to-code maps of the C++/GLSL contract (shader_contract.hpp).
#include "nimbus/render/core/shader_contract.hpp"

#include <stdexcept>

namespace nimbus::render {

int phase_code(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::Isotropic: return contract::PHASE_ISOTROPIC;
    case PhaseKind::HenyeyGreenstein: return contract::PHASE_HENYEY_GREENSTEIN;
    case PhaseKind::Schlick: return contract::PHASE_SCHLICK;
    case PhaseKind::Rayleigh: return contract::PHASE_RAYLEIGH;
  }
  throw std::invalid_argument("phase kind " + std::to_string(static_cast<int>(kind)) + " has no shader code");
}

int jitter_code(Jitter jitter) {
  switch (jitter) {
    case Jitter::None: return contract::JITTER_NONE;
    case Jitter::White: return contract::JITTER_WHITE;
    case Jitter::BlueNoise: return contract::JITTER_BLUE_NOISE;
  }
  throw std::invalid_argument("jitter " + std::to_string(static_cast<int>(jitter)) + " has no shader code");
}

int shaft_method_code(ShaftMethod::Kind kind) {
  switch (kind) {
    case ShaftMethod::Kind::RayMarch: return SHAFT_METHOD_RAYMARCH;
    case ShaftMethod::Kind::Analytic: return SHAFT_METHOD_ANALYTIC;
    case ShaftMethod::Kind::ShadowVolume: return SHAFT_METHOD_SHADOW_VOLUME;
    case ShaftMethod::Kind::Reference: break;
  }
  throw std::invalid_argument("shaft method 'reference' is the CPU renderer; no shader runs it");
}

int airlight_eval_code(AirlightMethod::Kind kind) {
  switch (kind) {
    case AirlightMethod::Stable: return contract::AIRLIGHT_EVAL_STABLE;
    case AirlightMethod::Table: return contract::AIRLIGHT_EVAL_TABLE;
    case AirlightMethod::RayMarch: return contract::AIRLIGHT_EVAL_RAYMARCH;
    case AirlightMethod::Quadrature: break;
  }
  throw std::invalid_argument("airlight method 'quadrature' is CPU only (double precision); no shader runs it");
}

}  // namespace nimbus::render
