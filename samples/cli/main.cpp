// nimbus: the command line. Usage errors exit 2, runtime errors exit 1, each with one line
// naming the bad input.
#include <cstdio>
#include <exception>
#include <string>

#include "cli.hpp"
#include "flag_checks.hpp"
#include "nimbus/base/memory.hpp"

namespace {

// Every error is one line on stderr, whatever it quotes (a key or argument holding a line break).
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nimbus: procedural cloud and gas volumes, and their renderer", "nimbus"};
  app.set_version_flag("--version", std::string("nimbus ") + NIMBUS_VERSION);
  app.require_subcommand(1);
  nimbus::cli::Action action;
  nimbus::cli::add_noise_command(app, action);
  nimbus::cli::add_bench_command(app, action);
  nimbus::cli::add_info_command(app, action);
  nimbus::cli::add_generate_command(app, action);
  nimbus::cli::add_presets_command(app, action);
  nimbus::cli::add_render_command(app, action);
  nimbus::cli::add_compare_command(app, action);
  nimbus::cli::add_airlight_command(app, action);
  nimbus::cli::add_view_command(app, action);
  nimbus::cli::add_merge_command(app, action);
  nimbus::cli::add_farm_command(app, action);
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known |= sub->check_name(argv[1]);
    if (!known) {
      std::fprintf(stderr, "nimbus: unknown command '%s' (try nimbus --help)\n", argv[1]);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "nimbus: %s\n", one_line(e.what()).c_str());
    return 2;
  }
  try {
    nimbus::cli::refuse_empty_values(app);
    return action ? action() : 0;
  } catch (const nimbus::cli::UsageError& e) {
    std::fprintf(stderr, "nimbus: %s\n", one_line(e.what()).c_str());
    return 2;
  } catch (const nimbus::OutOfMemoryRequest& e) {
    std::fprintf(stderr, "nimbus: %s\n", one_line(e.what()).c_str());
    return 2;
  } catch (const std::invalid_argument& e) {  // parameter validation
    std::fprintf(stderr, "nimbus: %s\n", one_line(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nimbus: error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
}
