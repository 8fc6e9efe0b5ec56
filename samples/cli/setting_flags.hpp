// The flags of the one table of render settings (render_settings.hpp): each registered with the
// table's name and help text (its range, unit and default appended), and checked against the
// table's range, so that `nimbus render`, a view state and Python agree on every value.
#pragma once
#include <optional>
#include <set>
#include <string>

#include "cli.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/sky/request_settings.hpp"

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

// Whether a setting's flag is the clouds' (`nimbus render FILE.vdb | --preset`): it has a flag and a
// field in the request, and is not one the render command registers for every mode (--fov and
// --exposure, render_args.cpp). render_modes.cpp reads it too.
bool is_cloud_setting(render::Setting id);

// Every cloud setting (above): --NAME VALUE sets the request's field as CLI11 reads it
// (request_settings.hpp), and records the setting in `given`. Text that is not a number, or a
// number out of the table's range, is a parse error naming the flag (and the range). A setting
// whose default is "auto" (--repeat-to) takes the text auto too: its default, not recorded.
void add_cloud_setting_options(CLI::App* cmd, render::RenderRequest& request, std::set<render::Setting>& given);

// UsageError "--NAME: must be in [a, b] unit, got v" unless the value is in the setting's range.
void check_flag(render::Setting id, double value);
inline void check_flag(render::Setting id, const std::optional<double>& value) {
  if (value) check_flag(id, *value);
}

}  // namespace nimbus::cli
