// The text forms of `nimbus render`'s typed cloud flags that are more than a number or a colour:
// each parser throws a UsageError naming its flag (typed_option.hpp turns it into a usage error).
#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace nimbus::cli {

// --spot DX,DY,DZ (Z up) -> a non-zero direction in the renderer's frame.
glm::dvec3 parse_spot_axis(const std::string& text);

// --spot-cone INNER,OUTER degrees, 0 < INNER <= OUTER <= 180.
glm::dvec2 parse_spot_cone(const std::string& text);

// --ambient: "auto" (nullopt: the sky's mean radiance, else 0) or V or R,G,B.
std::optional<glm::dvec3> parse_ambient(const std::string& text);

}  // namespace nimbus::cli
