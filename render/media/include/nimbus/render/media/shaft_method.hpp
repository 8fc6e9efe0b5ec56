// How the light shafts (single-scattered airlight) of the scene are computed: the three GPU
// methods the thesis compares and the exact CPU reference, as named on the command line.
#pragma once
#include <string>

#include "nimbus/render/media/airlight.hpp"

namespace nimbus::render {

enum class Jitter { None, White, BlueNoise };

struct ShaftMethod {
  enum class Kind { RayMarch, Analytic, ShadowVolume, Reference } kind = Kind::RayMarch;
  int steps = 64;  // ray-march samples per ray (RayMarch) or per ambiguous interval (ShadowVolume)
  AirlightMethod airlight;  // Analytic: Stable (any phase) or Table (isotropic only)
  Jitter jitter = Jitter::BlueNoise;
};

// "raymarch:N" (1 <= N <= 4096), "analytic" (= "analytic:stable"), "analytic:table:N"
// (16 <= N <= 1024), "shadowvolume:N", "reference". Throws std::invalid_argument naming the text.
ShaftMethod parse_shaft_method(const std::string& text);
std::string to_string(const ShaftMethod& method);

// The method's SHAFT_METHOD_* code in shaders/lib/contract.glsl (shafts.frag.glsl's METHOD);
// std::invalid_argument for Reference, which no shader runs.
int shaft_method_code(ShaftMethod::Kind kind);
// The jitter's JITTER_* code in shaders/lib/contract.glsl.
int jitter_code(Jitter jitter);

// "none", "white", "blue" -> Jitter; throws std::invalid_argument naming the text.
Jitter parse_jitter(const std::string& text);
std::string to_string(Jitter jitter);

}  // namespace nimbus::render
