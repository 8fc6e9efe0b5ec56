// Shared pieces of the nimbus command line: error kinds and subcommand registration.
#pragma once
#include <CLI/CLI.hpp>

#include <functional>
#include <stdexcept>
#include <string>

#include "nimbus/app/usage_error.hpp"

namespace nimbus::cli {

// Bad input from the user: exit code 2, one line naming the input (the app library's error kind).
using app::UsageError;

// `nimbus --check-only COMMAND ...`: the command checks every flag, input and output as it would,
// then stops before its work and exits 0 (nimbus farm slurm checks each task's command this way).
// Each command that supports it calls checks_done() where its checks end and its work begins.
struct ChecksPassed {};  // thrown by checks_done() in check-only mode; main() turns it into exit 0
void set_check_only(bool on);
bool check_only();
void checks_done();

// Each subcommand registers itself and sets the action that main() runs after parsing.
using Action = std::function<int()>;
void add_noise_command(CLI::App& app, Action& action);
void add_bench_command(CLI::App& app, Action& action);
void add_info_command(CLI::App& app, Action& action);
void add_generate_command(CLI::App& app, Action& action);
void add_presets_command(CLI::App& app, Action& action);
void add_render_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_airlight_command(CLI::App& app, Action& action);
void add_view_command(CLI::App& app, Action& action);
void add_merge_command(CLI::App& app, Action& action);
void add_farm_command(CLI::App& app, Action& action);

// Benchmarks, each a `nimbus bench NAME` subcommand.
void add_bench_noise(CLI::App& bench, Action& action);
void add_bench_volume(CLI::App& bench, Action& action);
void add_bench_shafts(CLI::App& bench, Action& action);
void add_bench_airlight(CLI::App& bench, Action& action);
void add_bench_clouds(CLI::App& bench, Action& action);
void add_bench_view(CLI::App& bench, Action& action);
void add_bench_gl(CLI::App& bench, Action& action);
void add_bench_look(CLI::App& bench, Action& action);
void add_bench_sky(CLI::App& bench, Action& action);

}  // namespace nimbus::cli
