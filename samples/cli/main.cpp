// nimbus: the command line. Usage errors exit 2, runtime errors exit 1, each with one line
// naming the bad input.
#include <cstdio>
#include <exception>
#include <string>

#include "cli.hpp"
#include "error_text.hpp"
#include "flag_checks.hpp"
#include "nimbus/base/memory.hpp"

namespace nimbus::cli {

// A command this build left out (-DNIMBUS_VIEWER_AND_BENCH=OFF, README command 1): it takes any
// arguments and says how to get it, as a usage error.
void add_absent_command(CLI::App& app, Action& action, const std::string& name, const std::string& what) {
  CLI::App* cmd = app.add_subcommand(name, "Not in this build: " + what + " (build with -DNIMBUS_VIEWER_AND_BENCH=ON)");
  cmd->allow_extras();
  cmd->set_help_flag();
  cmd->callback([&action, name, what] {
    action = [name, what]() -> int {
      throw UsageError(name + ": this build has no " + what.substr(4) + " (it was configured with "
                       "-DNIMBUS_VIEWER_AND_BENCH=OFF, as the README's main command does); build with README command 2, "
                       "or configure without that flag");
    };
  });
}

}  // namespace nimbus::cli

namespace {

using nimbus::cli::one_line;

// The commands whose checks end in checks_done(): the ones that write files.
bool supports_check_only(const std::string& command) {
  return command == "generate" || command == "render" || command == "view" || command == "merge" || command == "farm";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nimbus: procedural cloud and gas volumes, and their renderer", "nimbus"};
  app.set_version_flag("--version", std::string("nimbus ") + NIMBUS_VERSION);
  app.require_subcommand(1);
  bool check_only = false;
  app.add_flag("--check-only", check_only,
               "Check every flag, input and output of the command (generate, render, view, merge, farm slurm), "
               "then exit 0 without doing its work");
  nimbus::cli::Action action;
  nimbus::cli::add_noise_command(app, action);
#ifdef NIMBUS_VIEWER_AND_BENCH
  nimbus::cli::add_bench_command(app, action);
#else
  nimbus::cli::add_absent_command(app, action, "bench", "the benchmarks");
#endif
  nimbus::cli::add_info_command(app, action);
  nimbus::cli::add_generate_command(app, action);
  nimbus::cli::add_presets_command(app, action);
  nimbus::cli::add_render_command(app, action);
  nimbus::cli::add_compare_command(app, action);
  nimbus::cli::add_airlight_command(app, action);
#ifdef NIMBUS_VIEWER_AND_BENCH
  nimbus::cli::add_view_command(app, action);
#else
  nimbus::cli::add_absent_command(app, action, "view", "the interactive viewer");
#endif
  nimbus::cli::add_merge_command(app, action);
  nimbus::cli::add_farm_command(app, action);
  for (int i = 1; i < argc && argv[i][0] == '-'; ++i)  // the command after the program's own flags
    if (std::string(argv[i]) == "--check-only" && i + 1 < argc && argv[i + 1][0] != '-' && !supports_check_only(argv[i + 1])) {
      std::fprintf(stderr, "nimbus: --check-only: applies to generate, render, view, merge and farm, not to %s\n",
                   one_line(argv[i + 1]).substr(0, 40).c_str());
      return 2;
    }
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known |= sub->check_name(argv[1]);
    if (!known) {
      std::fprintf(stderr, "nimbus: unknown command '%s' (try nimbus --help)\n", one_line(argv[1]).substr(0, 40).c_str());
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
  } catch (const std::exception& e) {  // a file a flag reads as it is parsed (--request) cannot be read
    std::fprintf(stderr, "nimbus: error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
  try {
    nimbus::cli::refuse_empty_values(app);
    nimbus::cli::set_check_only(check_only);
    return action ? action() : 0;
  } catch (const nimbus::cli::ChecksPassed&) {
    return 0;
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
