// Parsing and printing of light-shaft method names (shaft_method.hpp).
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/base/input_limits.hpp"

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/shader_contract.hpp"

#include <optional>
#include <stdexcept>

namespace nimbus::render {
namespace {


bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

ShaftMethod parse_shaft_method(const std::string& text) {
  ShaftMethod m;
  if (starts_with(text, "raymarch:")) {
    m.kind = ShaftMethod::Kind::RayMarch;
    m.steps = parse_int_in(text.substr(9), 1, 4096, "method '" + echo(text) + "': the count");
  } else if (text == "analytic" || text == "analytic:stable") {
    m.kind = ShaftMethod::Kind::Analytic;
    m.airlight.kind = AirlightMethod::Stable;
  } else if (starts_with(text, "analytic:table:")) {
    m.kind = ShaftMethod::Kind::Analytic;
    m.airlight.kind = AirlightMethod::Table;
    m.airlight.n = parse_int_in(text.substr(15), 16, 1024, "method '" + echo(text) + "': the count");
  } else if (starts_with(text, "shadowvolume:")) {
    m.kind = ShaftMethod::Kind::ShadowVolume;
    m.steps = parse_int_in(text.substr(13), 1, 4096, "method '" + echo(text) + "': the count");
  } else if (text == "reference") {
    m.kind = ShaftMethod::Kind::Reference;
  } else {
    throw std::invalid_argument("method '" + echo(text) +
                                "': expected raymarch:N, analytic, analytic:table:N, "
                                "shadowvolume:N or reference");
  }
  return m;
}

std::string to_string(const ShaftMethod& m) {
  switch (m.kind) {
    case ShaftMethod::Kind::RayMarch: return "raymarch:" + std::to_string(m.steps);
    case ShaftMethod::Kind::Analytic:
      return m.airlight.kind == AirlightMethod::Table ? "analytic:table:" + std::to_string(m.airlight.n)
                                                      : std::string("analytic:stable");
    case ShaftMethod::Kind::ShadowVolume: return "shadowvolume:" + std::to_string(m.steps);
    case ShaftMethod::Kind::Reference: return "reference";
  }
  return "?";
}

int shaft_method_code(ShaftMethod::Kind kind) {
  switch (kind) {
    case ShaftMethod::Kind::RayMarch: return SHAFT_METHOD_RAYMARCH;
    case ShaftMethod::Kind::Analytic: return SHAFT_METHOD_ANALYTIC;
    case ShaftMethod::Kind::ShadowVolume: return SHAFT_METHOD_SHADOW_VOLUME;
    case ShaftMethod::Kind::Reference: break;
  }
  throw std::invalid_argument("shaft method 'reference' is the CPU renderer; no shader runs it");
}

int jitter_code(Jitter jitter) {
  switch (jitter) {
    case Jitter::None: return contract::JITTER_NONE;
    case Jitter::White: return contract::JITTER_WHITE;
    case Jitter::BlueNoise: return contract::JITTER_BLUE_NOISE;
  }
  throw std::invalid_argument("jitter " + std::to_string(static_cast<int>(jitter)) + " has no shader code");
}

Jitter parse_jitter(const std::string& text) {
  if (text == "none") return Jitter::None;
  if (text == "white") return Jitter::White;
  if (text == "blue") return Jitter::BlueNoise;
  throw std::invalid_argument("jitter '" + echo(text) + "': expected none, white or blue");
}

std::string to_string(Jitter j) {
  switch (j) {
    case Jitter::None: return "none";
    case Jitter::White: return "white";
    case Jitter::BlueNoise: return "blue";
  }
  return "?";
}

}  // namespace nimbus::render
