// Airlight methods by name ("quadrature", "stable", "table:N", "raymarch:N") and the CPU
// evaluation of a batch of queries with one of them.
#include <charconv>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/airlight.hpp"

namespace nimbus::render {

namespace {

int parse_count(const std::string& text, const std::string& digits, int lo, int hi) {
  int n = 0;
  const char* first = digits.data();
  const char* last = first + digits.size();
  const auto r = std::from_chars(first, last, n);
  if (digits.empty() || r.ec != std::errc() || r.ptr != last || n < lo || n > hi)
    throw std::invalid_argument("airlight method '" + text + "': N must be an integer in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  return n;
}

}  // namespace

AirlightMethod parse_airlight_method(const std::string& text) {
  if (text == "quadrature") return {AirlightMethod::Quadrature, 0};
  if (text == "stable") return {AirlightMethod::Stable, 0};
  const auto colon = text.find(':');
  const std::string name = text.substr(0, colon);
  if (colon != std::string::npos && name == "table")
    return {AirlightMethod::Table, parse_count(text, text.substr(colon + 1), 16, 1024)};
  if (colon != std::string::npos && name == "raymarch")
    return {AirlightMethod::RayMarch, parse_count(text, text.substr(colon + 1), 1, 10000000)};
  throw std::invalid_argument("airlight method '" + text + "': expected quadrature, stable, table:N or raymarch:N");
}

std::string to_string(const AirlightMethod& m) {
  switch (m.kind) {
    case AirlightMethod::Quadrature:
      return "quadrature";
    case AirlightMethod::Stable:
      return "stable";
    case AirlightMethod::Table:
      return "table:" + std::to_string(m.n);
    case AirlightMethod::RayMarch:
      return "raymarch:" + std::to_string(m.n);
  }
  return "stable";
}

std::vector<double> evaluate_airlight(const std::vector<AirlightQuery>& queries, const AirlightMethod& method) {
  std::vector<double> out;
  out.reserve(queries.size());
  std::unique_ptr<FTable> table;
  if (method.kind == AirlightMethod::Table) table = std::make_unique<FTable>(method.n);
  for (const AirlightQuery& q : queries) {
    switch (method.kind) {
      case AirlightMethod::Quadrature:
        out.push_back(airlight_quadrature(q));
        break;
      case AirlightMethod::Stable:
        out.push_back(airlight_stable(q));
        break;
      case AirlightMethod::Table:
        out.push_back(airlight_table(q, *table));
        break;
      case AirlightMethod::RayMarch:
        out.push_back(airlight_raymarch(q, method.n));
        break;
    }
  }
  return out;
}

}  // namespace nimbus::render
