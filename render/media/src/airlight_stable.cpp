// The float32 stable airlight on the CPU: shaders/lib/airlight.glsl compiled as C++ (glm), so
// that the CPU path and the shaders run the same source.
#include <glm/glm.hpp>

#include <cmath>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/shader_contract.hpp"

namespace nimbus::render::glsl {
using namespace glm;
using namespace ::nimbus::render::contract;  // lib/contract.glsl, already included: its guard skips it below
#include "lib/airlight.glsl"
}  // namespace nimbus::render::glsl

namespace nimbus::render {

double airlight_stable(const AirlightQuery& q) {
  validate(q);
  // cos and sin of gamma in double, then rounded: the shader receives the same two floats.
  return glsl::airlight_stable(float(q.beta), float(q.I0), float(q.Dsv), float(q.Dvp), float(std::cos(q.gamma)),
                               float(std::sin(q.gamma)));
}

double segment_airlight_stable(const SegmentQuery& q) {
  return glsl::point_segment_airlight(float(q.sigma_t), float(q.sigma_s), float(q.I0), float(q.Dsv),
                                      float(q.cos_gamma), float(q.sin_gamma), float(q.x0), float(q.x1),
                                      phase_code(q.phase.kind), float(q.phase.g));
}

double phase_value_float(const Phase& phase, double cos_theta) {
  return glsl::phase_value(phase_code(phase.kind), float(phase.g), float(cos_theta));
}

double sun_segment_airlight_stable(double sigma_t, double sigma_s, double E, double cos_theta, double x0, double x1,
                                   const Phase& phase) {
  return glsl::sun_segment_airlight(float(sigma_t), float(sigma_s), float(E), float(cos_theta), float(x0), float(x1),
                                    phase_code(phase.kind), float(phase.g));
}

}  // namespace nimbus::render
