// JSON files and checked values (json_io.hpp).
#include "nimbus/volume/json_io.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "nimbus/base/atomic_file.hpp"
#include "nimbus/base/input_limits.hpp"

namespace nimbus::volume {
namespace {

std::string range_text(double lo, double hi) {
  std::ostringstream o;
  o << "[" << lo << ", " << hi << "]";
  return o.str();
}

}  // namespace

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  const std::string text = read_regular_file(path, what + " '" + path + "'");  // size and file kind limits
  check_json_depth(text, what + " '" + path + "'");         // before the recursive parser sees it
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range.406 for a number such as 1e309
    throw std::runtime_error(what + " '" + path + "': not JSON (" + e.what() + ")");
  }
}

namespace {

// A value as a message quotes it; a string from a file or --set may hold bytes that are not
// UTF-8, which nlohmann's plain dump() throws on (type_error.316): they are shown as U+FFFD.
std::string quoted(const nlohmann::json& v) {
  return v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

std::string json_value_text(const nlohmann::json& v) {
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return echo(quoted(v));
}

void write_json_file(const std::string& path, const nlohmann::json& doc, const std::string& what) {
  const std::string text = doc.dump(2) + "\n";
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(what + " '" + path + "': cannot be written");
  });
}

double json_number(const nlohmann::json& v, const std::string& key, double lo, double hi) {
  if (!v.is_number()) throw std::invalid_argument(key + ": expected a number, got " + json_value_text(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw std::invalid_argument(key + " must be finite");
  if (x < lo || x > hi) throw std::invalid_argument(key + " must be in " + range_text(lo, hi) + ", got " + echo(quoted(v)));
  return x;
}

int json_integer(const nlohmann::json& v, const std::string& key, int lo, int hi) {
  if (!v.is_number_integer())
    throw std::invalid_argument(key + ": expected a whole number, got " + json_value_text(v));
  const long long x = v.get<long long>();
  if (x < lo || x > hi) throw std::invalid_argument(key + " must be in " + range_text(lo, hi) + ", got " + echo(quoted(v)));
  return static_cast<int>(x);
}

bool json_bool(const nlohmann::json& v, const std::string& key) {
  if (!v.is_boolean()) throw std::invalid_argument(key + ": expected true or false, got " + json_value_text(v));
  return v.get<bool>();
}

glm::dvec3 json_vec3(const nlohmann::json& v, const std::string& key, double limit) {
  if (!v.is_array() || v.size() != 3) throw std::invalid_argument(key + " must be [x, y, z]");
  return {json_number(v[0], key + "[0]", -limit, limit), json_number(v[1], key + "[1]", -limit, limit),
          json_number(v[2], key + "[2]", -limit, limit)};
}

}  // namespace nimbus::volume
