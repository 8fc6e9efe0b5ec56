// `nimbus presets [show NAME]`: the shipped cloud and gas presets and their documentation.
#include <cstdio>

#include "cli.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::cli {

void add_presets_command(CLI::App& app, Action& action) {
  CLI::App* cmd = app.add_subcommand("presets", "List the cloud and gas presets, or show one");
  auto name = std::make_shared<std::string>();
  CLI::App* show = cmd->add_subcommand("show", "Print a preset: its parameters and what each does");
  show->add_option("name", *name, "preset name (see nimbus presets)")->required();
  cmd->callback([&action, cmd, show, name] {
    if (show->parsed()) {
      action = [name] {
        nlohmann::json doc;
        try {
          doc = volume::load_preset(*name);
        } catch (const std::invalid_argument& e) {
          throw UsageError(e.what());
        }
        std::printf("%s\n", doc.dump(2).c_str());
        return 0;
      };
    } else {
      action = [] {
        for (const auto& p : volume::list_presets())
          std::printf("%-40s %-14s %s\n", p.name.c_str(), p.genus.c_str(), p.description.c_str());
        return 0;
      };
    }
    (void)cmd;
  });
}

}  // namespace nimbus::cli
