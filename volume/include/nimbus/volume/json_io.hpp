// JSON documents nimbus reads and writes (sky files, view states, viewer scripts): whole files
// read with errors that name them, written atomically, and values checked with errors that name
// their key ("sky.wind[0] must be in [-200, 200]").
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include <glm/vec3.hpp>

namespace nimbus::volume {

// The file parsed. std::runtime_error "<what> '<path>': cannot be read", "...: not JSON (...)",
// or a refusal under the input limits (nimbus/base/input_limits.hpp: a regular file of at most
// 16 MiB, nested at most 64 deep), checked before the parser runs.
nlohmann::json read_json_file(const std::string& path, const std::string& what);
// A value as an error message shows what was found instead: null, true, "abc" (at most 40
// characters, then ...), 3.5, an array, an object.
std::string json_value_text(const nlohmann::json& v);
// Two-space indented, newline-terminated, atomically; std::runtime_error naming the file.
void write_json_file(const std::string& path, const nlohmann::json& doc, const std::string& what);

// Checked values: std::invalid_argument naming `key` when the type is wrong, the value is not
// finite, or it lies outside [lo, hi].
double json_number(const nlohmann::json& v, const std::string& key, double lo = -1e300, double hi = 1e300);
int json_integer(const nlohmann::json& v, const std::string& key, int lo, int hi);
bool json_bool(const nlohmann::json& v, const std::string& key);
// [x, y, z], each within [-limit, limit].
glm::dvec3 json_vec3(const nlohmann::json& v, const std::string& key, double limit = 1e300);

}  // namespace nimbus::volume
