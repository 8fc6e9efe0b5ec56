// A Light packed for the shaders, and their evaluation of it compiled as C++ (light_record.hpp).
#include "nimbus/render/core/light_record.hpp"

#include <cmath>

namespace nimbus::render {
namespace glsl {
// In an unnamed namespace: lib/spot_cone.glsl is compiled into other files too (spot_airlight.cpp),
// and each copy must stay in its own file.
namespace {
using namespace glm;
#include "lib/light_eval.glsl"
}  // namespace
}  // namespace glsl

namespace {
glm::vec3 to_float3(const glm::dvec3& v) { return glm::vec3(v); }
}  // namespace

LightRecord light_record(const Light& light) {
  validate(light);
  LightRecord r = no_light_record();
  if (light.kind == LightKind::Sun) {
    r.position = glm::vec4(to_float3(glm::normalize(light.direction_to_sun)), float(contract::LIGHT_SUN));
    r.power = glm::vec4(to_float3(light.irradiance_w_m2), 0.0f);
    return r;
  }
  r.position = glm::vec4(to_float3(light.position_m), float(contract::LIGHT_LAMP));
  r.power = glm::vec4(to_float3(light.intensity_w_sr), static_cast<float>(light.min_distance_m));
  if (is_spot(light)) {
    r.spot = glm::vec4(to_float3(glm::normalize(light.spot_axis)), 1.0f);
    r.spot_cos = glm::vec4(static_cast<float>(std::cos(light.spot_outer_rad)),
                           static_cast<float>(std::cos(light.spot_inner_rad)), 0.0f, 0.0f);
  }
  return r;
}

LightRecord no_light_record() {
  LightRecord r;
  r.position = glm::vec4(0.0f, 1.0f, 0.0f, float(contract::LIGHT_SUN));
  r.power = glm::vec4(0.0f);
  r.spot = glm::vec4(0.0f);
  r.spot_cos = glm::vec4(0.0f);
  return r;
}

LightRecordAt light_record_at(const LightRecord& light, const glm::vec3& x) {
  LightRecordAt a;
  a.propagation = glsl::light_propagation(light, x);
  a.irradiance_w_m2 = glsl::light_irradiance(light, x, a.propagation);
  return a;
}

}  // namespace nimbus::render
