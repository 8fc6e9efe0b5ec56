// Command-line checks shared by every command (flag_checks.hpp).
#include "flag_checks.hpp"

#include <stdexcept>

namespace nimbus::cli {
namespace {

void refuse_empty_in(const CLI::App& app) {
  for (const CLI::Option* opt : app.get_options()) {
    if (opt->count() == 0 || opt->get_type_size_max() == 0) continue;  // not given, or a flag
    for (const std::string& value : opt->results())
      if (value.empty()) throw UsageError(opt->get_name() + ": the value is empty (leave the flag out for its default)");
  }
  for (const CLI::App* sub : app.get_subcommands()) refuse_empty_in(*sub);
}

}  // namespace

void refuse_empty_values(const CLI::App& app) { refuse_empty_in(app); }

void check_flags_apply(const CLI::App& cmd, const std::vector<FlagModes>& table, unsigned mode,
                       const std::vector<std::string>& mode_names) {
  const auto modes_text = [&](unsigned modes) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < mode_names.size(); ++i)
      if (modes & (1u << i)) names.push_back(mode_names[i]);
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i)
      text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return text;
  };
  for (const CLI::Option* opt : cmd.get_options()) {
    if (opt->count() == 0) continue;
    const std::string name = opt->get_name();
    if (name == "--help") continue;
    const FlagModes* rule = nullptr;
    for (const FlagModes& r : table)
      if (r.flag == name) rule = &r;
    if (!rule) throw std::logic_error("flag " + name + " is missing from its command's table of modes");
    if (!(rule->modes & mode))
      throw UsageError(name + ": applies to " + modes_text(rule->modes) + ", not to " + modes_text(mode));
  }
}

}  // namespace nimbus::cli
