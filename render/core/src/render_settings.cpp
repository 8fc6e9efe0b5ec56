// The render settings' table: ranges checked and printed (render_settings.hpp).
#include "nimbus/render/core/render_settings.hpp"

#include <cmath>
#include <stdexcept>

#include "nimbus/base/validate.hpp"

namespace nimbus::render {
namespace {

constexpr bool in_order() {
  for (std::size_t i = 0; i < kRenderSettings.size(); ++i)
    if (std::size_t(kRenderSettings[i].id) != i) return false;
  return true;
}
static_assert(in_order(), "kRenderSettings must list the settings in Setting's order");

// Every default within its own range: a table that breaks it fails to compile.
constexpr bool defaults_in_range() {
  for (const RenderSetting& s : kRenderSettings)
    if (!in_range(s, s.still_default) || !in_range(s, s.view_default)) return false;
  return true;
}
static_assert(defaults_in_range(), "every default of kRenderSettings must lie in its range");

}  // namespace

std::string range_text(const RenderSetting& s) {
  // A count in full (268435456, not number_text's 2.68435e+08).
  const auto bound = [&](double v) { return s.integer ? std::to_string(std::int64_t(v)) : number_text(v); };
  const std::string text = (s.min_open ? "(" : "[") + bound(s.min) + ", " + bound(s.max) + (s.max_open ? ")" : "]");
  return s.unit.empty() ? text : text + " " + std::string(s.unit);
}

void check_setting(Setting id, double value, const std::string& name) {
  const RenderSetting& s = setting(id);
  if (in_range(s, value)) return;
  // A whole count in full; anything else (a fraction, NaN, 1e300) as number_text writes it.
  const bool whole = std::abs(value) < 9e15 && value == std::floor(value);
  const std::string got = s.integer && whole ? std::to_string(std::int64_t(value)) : number_text(value);
  throw std::invalid_argument(name + ": must be in " + range_text(s) + ", got " + got);
}

std::string flag_name(const RenderSetting& s) { return s.flag.empty() ? std::string() : "--" + std::string(s.flag); }

}  // namespace nimbus::render
