// The flags of the one table of render settings (render_settings.hpp): each registered with the
// table's name and help text (its range, unit and default appended), and checked against the
// table's range, so that `nimbus render`, a view state and Python agree on every value.
#pragma once
#include <optional>
#include <string>

#include "cli.hpp"
#include "nimbus/render/core/render_settings.hpp"

namespace nimbus::cli {

// "Half-angle slices across the clouds, [2, 4096]" with the default in words where it has one.
std::string setting_help(render::Setting id);

// --NAME for the setting, its help from the table; the field's initial value is shown as the
// default where the table's default is a number.
template <typename T>
CLI::Option* add_setting_option(CLI::App* cmd, render::Setting id, T& field) {
  const render::RenderSetting& s = render::setting(id);
  CLI::Option* option = cmd->add_option(render::flag_name(s), field, setting_help(id));
  if (s.default_text.empty()) option->capture_default_str();
  return option;
}

// UsageError "--NAME: must be in [a, b] unit, got v" unless the value is in the setting's range.
void check_flag(render::Setting id, double value);
inline void check_flag(render::Setting id, const std::optional<double>& value) {
  if (value) check_flag(id, *value);
}

}  // namespace nimbus::cli
