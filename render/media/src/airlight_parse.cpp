// Airlight methods by name ("quadrature", "stable", "table:N", "raymarch:N") and the CPU
// evaluation of a batch of queries with one of them.
#include <optional>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/base/validate.hpp"
#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/shader_contract.hpp"

namespace nimbus::render {


AirlightMethod parse_airlight_method(const std::string& text) {
  if (text == "quadrature") return {AirlightMethod::Quadrature, 0};
  if (text == "stable") return {AirlightMethod::Stable, 0};
  const auto colon = text.find(':');
  const std::string name = text.substr(0, colon);
  if (colon != std::string::npos && name == "table")
    return {AirlightMethod::Table, parse_int_in(text.substr(colon + 1), 16, 1024, "airlight method '" + text + "': N")};
  if (colon != std::string::npos && name == "raymarch")
    return {AirlightMethod::RayMarch, parse_int_in(text.substr(colon + 1), 1, 10000000, "airlight method '" + text + "': N")};
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

int airlight_eval_code(AirlightMethod::Kind kind) {
  switch (kind) {
    case AirlightMethod::Stable: return contract::AIRLIGHT_EVAL_STABLE;
    case AirlightMethod::Table: return contract::AIRLIGHT_EVAL_TABLE;
    case AirlightMethod::RayMarch: return contract::AIRLIGHT_EVAL_RAYMARCH;
    case AirlightMethod::Quadrature: break;
  }
  throw std::invalid_argument("airlight method 'quadrature' is CPU only (double precision); no shader runs it");
}

std::vector<double> evaluate_airlight(const std::vector<AirlightQuery>& queries, const AirlightMethod& method,
                                      const Phase& phase) {
  const bool isotropic = phase.kind == PhaseKind::Isotropic;
  if (method.kind == AirlightMethod::Table && !isotropic)
    throw std::invalid_argument("airlight method '" + to_string(method) + "' is isotropic only (Sun's F(u, v)); phase '" +
                                to_string(phase) + "' needs stable, raymarch:N or quadrature");
  std::vector<double> out;
  out.reserve(queries.size());
  std::unique_ptr<FTable> table;
  if (method.kind == AirlightMethod::Table) table = std::make_unique<FTable>(method.n);
  auto segment = [&](const AirlightQuery& q) {  // Sun's query as a segment from the eye
    validate(q);
    return to_segment(q, phase);
  };
  for (const AirlightQuery& q : queries) {
    switch (method.kind) {
      case AirlightMethod::Quadrature:
        out.push_back(isotropic ? airlight_quadrature(q) : segment_airlight_quadrature(segment(q)));
        break;
      case AirlightMethod::Stable:
        out.push_back(isotropic ? airlight_stable(q) : segment_airlight_stable(segment(q)));
        break;
      case AirlightMethod::Table:
        out.push_back(airlight_table(q, *table));
        break;
      case AirlightMethod::RayMarch:
        out.push_back(airlight_raymarch(q, method.n, phase));
        break;
    }
  }
  return out;
}

}  // namespace nimbus::render
