// Double-precision scene values (metres, radiance) rounded to the floats the GPU takes.
#pragma once
#include <glm/glm.hpp>

namespace nimbus::render {

inline glm::vec2 to_float(const glm::dvec2& v) { return glm::vec2(v); }
inline glm::vec3 to_float(const glm::dvec3& v) { return glm::vec3(v); }
inline glm::vec4 to_float(const glm::dvec4& v) { return glm::vec4(v); }
inline glm::mat4 to_float(const glm::dmat4& m) { return glm::mat4(m); }

}  // namespace nimbus::render
