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
    for (double v : {s.still_default, s.view_default}) {
      if (s.min_open ? !(v > s.min) : !(v >= s.min)) return false;
      if (s.max_open ? !(v < s.max) : !(v <= s.max)) return false;
    }
  return true;
}
static_assert(defaults_in_range(), "every default of kRenderSettings must lie in its range");

}  // namespace

bool in_range(const RenderSetting& s, double v) {
  if (!std::isfinite(v)) return false;
  if (s.integer && v != std::floor(v)) return false;
  if (s.min_open ? !(v > s.min) : !(v >= s.min)) return false;
  return s.max_open ? v < s.max : v <= s.max;
}

std::string range_text(const RenderSetting& s) {
  std::string text = std::string(s.min_open ? "(" : "[") + number_text(s.min) + ", " + number_text(s.max) +
                     (s.max_open ? ")" : "]");
  // 268435456 reads better than number_text's 2.68435e+08 for a count
  if (s.integer) text = std::string(s.min_open ? "(" : "[") + std::to_string(std::int64_t(s.min)) + ", " +
                        std::to_string(std::int64_t(s.max)) + (s.max_open ? ")" : "]");
  return s.unit.empty() ? text : text + " " + std::string(s.unit);
}

void check_setting(Setting id, double value, const std::string& name) {
  const RenderSetting& s = setting(id);
  if (in_range(s, value)) return;
  const std::string got = s.integer && std::isfinite(value) && std::abs(value) < 9e15
                              ? std::to_string(std::int64_t(value))
                              : number_text(value);
  throw std::invalid_argument(name + ": must be in " + range_text(s) +
                              ", got " + got);
}

std::string flag_name(const RenderSetting& s) { return s.flag.empty() ? std::string() : "--" + std::string(s.flag); }

}  // namespace nimbus::render
