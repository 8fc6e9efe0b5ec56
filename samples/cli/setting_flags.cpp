// The table's flags: help text and range checks (setting_flags.hpp).
#include "setting_flags.hpp"

#include <stdexcept>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/validate.hpp"
#include "typed_option.hpp"

namespace nimbus::cli {

std::string setting_help(render::Setting id) {
  const render::RenderSetting& s = render::setting(id);
  std::string help = std::string(s.help) + ", " + render::range_text(s);
  if (!s.default_text.empty()) help += " (default: " + std::string(s.default_text) + ")";
  return help;
}

bool is_cloud_setting(render::Setting id) {
  return !render::setting(id).flag.empty() && render::in_request(id) && id != render::Setting::Fov &&
         id != render::Setting::Exposure;
}

void add_cloud_setting_options(CLI::App* cmd, render::RenderRequest& request, std::set<render::Setting>& given) {
  for (const render::RenderSetting& s : render::kRenderSettings) {
    if (!is_cloud_setting(s.id)) continue;
    const std::string name = render::flag_name(s);
    const bool takes_auto = s.default_text.rfind("auto", 0) == 0;
    const auto set = [&request, &given, &s, name, takes_auto](const std::string& text) {
      if (takes_auto && text == "auto") {
        render::set_setting_value(request, s.id, s.still_default, name);
        given.erase(s.id);
        return;
      }
      const std::optional<double> v = parse_double(text);
      if (!v)
        throw UsageError(name + ": '" + echo(text, 40) + "' is not " + (takes_auto ? "auto or " : "") +
                         (s.integer ? "an integer" : "a number"));
      try {
        render::set_setting_value(request, s.id, *v, name);  // its range: check_setting's message
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
      given.insert(s.id);
    };
    CLI::Option* option = cmd->add_option_function<std::string>(
        name, [set, name](const std::string& text) { parse_flag_text(name, text, set); }, setting_help(s.id));
    option->type_name(s.integer ? "INT" : "FLOAT");
    if (s.default_text.empty())
      option->default_str(s.integer ? std::to_string(std::int64_t(s.still_default)) : number_text(s.still_default));
  }
}

void check_flag(render::Setting id, double value) {
  try {
    render::check_setting(id, value, render::flag_name(render::setting(id)));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace nimbus::cli
