// Argument checks and strict number parsing (validate.hpp).
#include "nimbus/base/validate.hpp"

#include <cstdio>

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace nimbus {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

bool all_finite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

std::optional<double> parse_double(std::string_view text) {
  double v = 0.0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto r = std::from_chars(first, last, v);
  if (text.empty() || r.ec != std::errc() || r.ptr != last) return std::nullopt;
  return v;
}

std::optional<int> parse_int_in(std::string_view text, int lo, int hi) {
  int n = 0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto r = std::from_chars(first, last, n);
  if (text.empty() || r.ec != std::errc() || r.ptr != last || n < lo || n > hi) return std::nullopt;
  return n;
}

int parse_int_in(std::string_view text, int lo, int hi, const std::string& what) {
  const std::optional<int> n = parse_int_in(text, lo, hi);
  if (!n)
    throw std::invalid_argument(what + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return *n;
}

}  // namespace nimbus
