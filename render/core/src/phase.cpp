// Phase functions (thesis eqs. 13-17) in double precision, and their text form "isotropic",
// "hg:G", "schlick:G", "rayleigh", "dual:GF,GB,W" used on the command line and in files.
#include "nimbus/render/core/phase.hpp"
#include "nimbus/base/input_limits.hpp"

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/shader_contract.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace nimbus::render {

namespace {

constexpr double kInv4Pi = 1.0 / (4.0 * std::numbers::pi);
constexpr double kSchlickMaxK = 0.999;  // same bound as shaders/lib/phase.glsl

constexpr const char* kPhaseForms = "isotropic, hg:G, schlick:G, rayleigh or dual:GF,GB,W";

std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Eq. 14 with 1 + g^2 - 2 g cos = (1 - g)^2 + 2 g (1 - cos), exact near the peak.
double henyey_greenstein(double g, double c) {
  const double denom = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - c);
  return kInv4Pi * (1.0 - g * g) / (denom * std::sqrt(denom));
}

// "GF,GB,W" after "dual:".
Phase parse_dual(const std::string& text) {
  std::stringstream ss(text.substr(5));
  double part[3] = {0.0, 0.0, 0.0};
  int n = 0;
  for (std::string item; std::getline(ss, item, ',');) {
    if (n == 3) throw std::invalid_argument("phase '" + echo(text) + "': expected dual:GF,GB,W");
    const std::optional<double> v = parse_double(item);
    if (!v) throw std::invalid_argument("phase '" + echo(text) + "': '" + echo(item) + "' is not a number");
    part[n++] = *v;
  }
  if (n != 3) throw std::invalid_argument("phase '" + echo(text) + "': expected dual:GF,GB,W");
  return dual_lobe_phase(part[0], part[1], part[2]);
}

}  // namespace

double schlick_k(double g) { return 1.55 * g - 0.55 * g * g * g; }  // thesis eq. 16

bool phase_takes_g(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::Isotropic: return false;
    case PhaseKind::HenyeyGreenstein: return true;
    case PhaseKind::Schlick: return true;
    case PhaseKind::Rayleigh: return false;
    case PhaseKind::DualHenyeyGreenstein: return true;
  }
  return false;
}

void validate(const Phase& p, const std::string& what) {
  auto in_g = [](double g) { return std::isfinite(g) && g > -1.0 && g < 1.0; };
  const bool dual = p.kind == PhaseKind::DualHenyeyGreenstein;  // named as in dual:GF,GB,W
  auto bad = [&](const char* field, const char* range, double v) {
    return std::invalid_argument(what + " " + field + " must be in " + range + " (got " + num(v) + ")");
  };
  if (phase_takes_g(p.kind) && !in_g(p.g)) throw bad(dual ? "g (GF)" : "g", "(-1, 1)", p.g);
  if (!dual) return;
  if (!in_g(p.g_back)) throw bad("g_back (GB)", "(-1, 1)", p.g_back);
  if (!(std::isfinite(p.forward_weight) && p.forward_weight >= 0.0 && p.forward_weight <= 1.0))
    throw bad("forward_weight (W)", "[0, 1]", p.forward_weight);
}

Phase as_dual_lobes(const Phase& p) {
  switch (p.kind) {
    case PhaseKind::Isotropic: return dual_lobe_phase(0.0, 0.0, 1.0);
    case PhaseKind::HenyeyGreenstein: return dual_lobe_phase(p.g, 0.0, 1.0);
    case PhaseKind::DualHenyeyGreenstein: return p;
    case PhaseKind::Schlick:
    case PhaseKind::Rayleigh: break;
  }
  throw std::invalid_argument("phase " + to_string(p) +
                              " is not a sum of Henyey-Greenstein lobes: clouds take isotropic, hg:G or dual:GF,GB,W");
}

int phase_code(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::Isotropic: return contract::PHASE_ISOTROPIC;
    case PhaseKind::HenyeyGreenstein: return contract::PHASE_HENYEY_GREENSTEIN;
    case PhaseKind::Schlick: return contract::PHASE_SCHLICK;
    case PhaseKind::Rayleigh: return contract::PHASE_RAYLEIGH;
    case PhaseKind::DualHenyeyGreenstein: break;  // the fog's shaders take one lobe
  }
  throw std::invalid_argument("phase kind " + std::to_string(static_cast<int>(kind)) + " has no fog shader code");
}

double phase_value(const Phase& phase, double cos_theta) {
  const double c = std::clamp(cos_theta, -1.0, 1.0);
  switch (phase.kind) {
    case PhaseKind::Isotropic:
      return kInv4Pi;  // thesis eq. 13
    case PhaseKind::HenyeyGreenstein:
      return henyey_greenstein(phase.g, c);
    case PhaseKind::DualHenyeyGreenstein:
      return phase.forward_weight * henyey_greenstein(phase.g, c) +
             (1.0 - phase.forward_weight) * henyey_greenstein(phase.g_back, c);
    case PhaseKind::Schlick: {
      // Thesis eq. 15 as printed has (1 + k cos theta)^2, which peaks backwards for k > 0;
      // we use 1 - k cos theta so that g > 0 means forward scattering as for
      // Henyey-Greenstein (the usual form of Schlick's approximation).
      // Eq. 16 gives |k| > 1 for |g| > 0.938; k is kept inside (-1, 1) there.
      const double k = std::clamp(schlick_k(phase.g), -kSchlickMaxK, kSchlickMaxK);
      const double denom = 1.0 - k * c;
      return kInv4Pi * (1.0 - k * k) / (denom * denom);
    }
    case PhaseKind::Rayleigh:
      return 3.0 / (16.0 * std::numbers::pi) * (1.0 + c * c);  // thesis eq. 17
  }
  return kInv4Pi;
}

Phase parse_phase(const std::string& text) {
  if (text == "isotropic") return {PhaseKind::Isotropic, 0.0};
  if (text == "rayleigh") return {PhaseKind::Rayleigh, 0.0};
  if (text.rfind("dual:", 0) == 0) {
    const Phase p = parse_dual(text);
    validate(p, "phase '" + echo(text) + "':");
    return p;
  }
  const auto colon = text.find(':');
  if (colon != std::string::npos) {
    const std::string name = text.substr(0, colon);
    const std::string value = text.substr(colon + 1);
    PhaseKind kind;
    if (name == "hg")
      kind = PhaseKind::HenyeyGreenstein;
    else if (name == "schlick")
      kind = PhaseKind::Schlick;
    else
      throw std::invalid_argument("phase '" + echo(text) + "': expected " + kPhaseForms);
    const std::optional<double> g = parse_double(value);
    if (!g) throw std::invalid_argument("phase '" + echo(text) + "': G is not a number");
    const Phase p{kind, *g};
    validate(p, "phase '" + echo(text) + "':");
    return p;
  }
  throw std::invalid_argument("phase '" + echo(text) + "': expected " + kPhaseForms);
}

std::string to_string(const Phase& phase) {
  switch (phase.kind) {
    case PhaseKind::Isotropic:
      return "isotropic";
    case PhaseKind::HenyeyGreenstein:
      return "hg:" + num(phase.g);
    case PhaseKind::Schlick:
      return "schlick:" + num(phase.g);
    case PhaseKind::Rayleigh:
      return "rayleigh";
    case PhaseKind::DualHenyeyGreenstein:
      return "dual:" + num(phase.g) + "," + num(phase.g_back) + "," + num(phase.forward_weight);
  }
  return "isotropic";
}

}  // namespace nimbus::render
