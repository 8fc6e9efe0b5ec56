// The table's flags: help text and range checks (setting_flags.hpp).
#include "setting_flags.hpp"

#include <stdexcept>

namespace nimbus::cli {

std::string setting_help(render::Setting id) {
  const render::RenderSetting& s = render::setting(id);
  std::string help = std::string(s.help) + ", " + render::range_text(s);
  if (!s.default_text.empty()) help += " (default: " + std::string(s.default_text) + ")";
  return help;
}

void check_flag(render::Setting id, double value) {
  try {
    render::check_setting(id, value, render::flag_name(render::setting(id)));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace nimbus::cli
