// Parsers of the typed cloud flags (cloud_flags.hpp).
#include "cloud_flags.hpp"

#include "cli.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "render_args.hpp"
#include "render_clouds_plan.hpp"

namespace nimbus::cli {

glm::dvec3 parse_spot_axis(const std::string& text) {
  const glm::dvec3 axis = parse_world_vec3("--spot", text);
  if (!(glm::length(axis) > 0.0)) throw UsageError("--spot: '" + text + "' must be a non-zero direction");
  return axis;
}

glm::dvec2 parse_spot_cone(const std::string& text) {
  const std::size_t comma = text.find(',');
  const std::optional<double> inner = comma == std::string::npos ? std::nullopt : parse_double(text.substr(0, comma));
  const std::optional<double> outer = comma == std::string::npos ? std::nullopt : parse_double(text.substr(comma + 1));
  if (!inner || !outer || !(*inner > 0.0) || !(*inner <= *outer) || !(*outer <= 180.0))
    throw UsageError("--spot-cone: '" + text + "' must be INNER,OUTER degrees with 0 < INNER <= OUTER <= 180");
  return {*inner, *outer};
}

std::optional<glm::dvec3> parse_ambient(const std::string& text) {
  if (text == "auto") return std::nullopt;
  return parse_colour("--ambient", text);
}

}  // namespace nimbus::cli
