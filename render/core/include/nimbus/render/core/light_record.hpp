// A Light (light.hpp) as the shaders read it: LightRecord, the struct of
// shaders/lib/light_record.glsl compiled as C++ (glm floats, std140: four vec4s), packed by
// light_record(); and the shaders' one light evaluation, lib/light_eval.glsl compiled as C++,
// so that the CPU can check what the GPU computes against light_at in double.
#pragma once
#include <cstddef>

#include <glm/glm.hpp>

#include "nimbus/render/core/light.hpp"
#include "nimbus/render/core/shader_contract.hpp"  // before the record: its guard keeps one contract

namespace nimbus::render::glsl {
using glm::vec4;
#include "lib/light_record.glsl"
}  // namespace nimbus::render::glsl

namespace nimbus::render {

using LightRecord = glsl::LightRecord;
static_assert(sizeof(LightRecord) == 64 && offsetof(LightRecord, power) == 16 && offsetof(LightRecord, spot) == 32 &&
                  offsetof(LightRecord, spot_cos) == 48,
              "LightRecord must follow std140 as lib/light_record.glsl declares it");

// The light in float as the shaders read it: the sun's direction normalised, a spot's axis
// normalised and its cones as cosines. Throws std::invalid_argument as validate(Light) does.
LightRecord light_record(const Light& light);

// No light: a sun of zero irradiance straight up (every member finite).
LightRecord no_light_record();

// lib/light_eval.glsl on the CPU: the unit propagation direction at x and the unshadowed
// irradiance there (W m^-2 per channel), in float as a shader computes them.
struct LightRecordAt {
  glm::vec3 propagation{0.0f};
  glm::vec3 irradiance_w_m2{0.0f};
};
LightRecordAt light_record_at(const LightRecord& light, const glm::vec3& x);

}  // namespace nimbus::render
