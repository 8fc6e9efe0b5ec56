// Reading the view state's and the render request's JSON: each value named by its key in errors
// (view_state.cpp, render_request.cpp).
#pragma once
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/volume/json_io.hpp"

namespace nimbus::render::json_read {

using json = nlohmann::json;

[[noreturn]] inline void bad(const std::string& m) { throw std::invalid_argument(m); }

inline double number(const json& v, const std::string& key) { return volume::json_number(v, key); }
inline int integer(const json& v, const std::string& key) { return volume::json_integer(v, key, -1000000000, 1000000000); }
inline glm::dvec3 vec3(const json& v, const std::string& key) { return volume::json_vec3(v, key); }
inline json to_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// A string value read through its parser (parse_cloud_phase, parse_shaft_method...): the key is
// named when it is not a string (`expected` says what it should be) or the parser refuses it.
template <typename Parse>
auto parsed(const json& v, const std::string& key, const char* expected, Parse parse) {
  if (!v.is_string()) bad(key + " must be " + expected);
  try {
    return parse(v.get<std::string>());
  } catch (const std::invalid_argument& e) {
    bad(key + ": " + e.what());
  }
}

// Calls f(key, value, its full key) for every member of the object `v` at `key`, which must be one.
template <typename F>
void members(const json& v, const std::string& key, F f) {
  if (!v.is_object()) bad(key + " must be an object");
  for (const auto& [k, x] : v.items()) f(k, x, key + "." + echo(k));  // a key read from a file: short, one line
}

}  // namespace nimbus::render::json_read
