// Phase functions of the medium (thesis eqs. 13-17) in double precision, and their text form
// "isotropic", "hg:G", "schlick:G", "rayleigh" used on the command line.
#include "nimbus/render/core/phase.hpp"
#include "nimbus/base/input_limits.hpp"

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/shader_contract.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

namespace nimbus::render {

namespace {

constexpr double kInv4Pi = 1.0 / (4.0 * std::numbers::pi);
constexpr double kSchlickMaxK = 0.999;  // same bound as shaders/lib/phase.glsl

void check_g(double g, const std::string& text) {
  if (!(g > -1.0 && g < 1.0))
    throw std::invalid_argument("phase '" + echo(text) + "': g must be in (-1, 1)");
}

}  // namespace

double schlick_k(double g) { return 1.55 * g - 0.55 * g * g * g; }  // thesis eq. 16

bool phase_takes_g(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::Isotropic: return false;
    case PhaseKind::HenyeyGreenstein: return true;
    case PhaseKind::Schlick: return true;
    case PhaseKind::Rayleigh: return false;
  }
  return false;
}

int phase_code(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::Isotropic: return contract::PHASE_ISOTROPIC;
    case PhaseKind::HenyeyGreenstein: return contract::PHASE_HENYEY_GREENSTEIN;
    case PhaseKind::Schlick: return contract::PHASE_SCHLICK;
    case PhaseKind::Rayleigh: return contract::PHASE_RAYLEIGH;
  }
  throw std::invalid_argument("phase kind " + std::to_string(static_cast<int>(kind)) + " has no shader code");
}

double phase_value(const Phase& phase, double cos_theta) {
  const double c = std::clamp(cos_theta, -1.0, 1.0);
  switch (phase.kind) {
    case PhaseKind::Isotropic:
      return kInv4Pi;  // thesis eq. 13
    case PhaseKind::HenyeyGreenstein: {
      // Thesis eq. 14 with 1 + g^2 - 2 g cos = (1 - g)^2 + 2 g (1 - cos), exact near the peak.
      const double g = phase.g;
      const double denom = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - c);
      return kInv4Pi * (1.0 - g * g) / (denom * std::sqrt(denom));
    }
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
      throw std::invalid_argument("phase '" + echo(text) + "': expected isotropic, hg:G, schlick:G or rayleigh");
    const std::optional<double> g = parse_double(value);
    if (!g) throw std::invalid_argument("phase '" + echo(text) + "': G is not a number");
    check_g(*g, text);
    return {kind, *g};
  }
  throw std::invalid_argument("phase '" + echo(text) + "': expected isotropic, hg:G, schlick:G or rayleigh");
}

std::string to_string(const Phase& phase) {
  auto num = [](double g) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, g);
    return std::string(buf, r.ptr);
  };
  switch (phase.kind) {
    case PhaseKind::Isotropic:
      return "isotropic";
    case PhaseKind::HenyeyGreenstein:
      return "hg:" + num(phase.g);
    case PhaseKind::Schlick:
      return "schlick:" + num(phase.g);
    case PhaseKind::Rayleigh:
      return "rayleigh";
  }
  return "isotropic";
}

}  // namespace nimbus::render
