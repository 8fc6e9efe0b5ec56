// `nimbus bench NAME`: benchmarks that report speed beside error, against named anchors.
#include "cli/cli.hpp"

namespace nimbus::cli {

void add_bench_command(CLI::App& app, Action& action) {
  CLI::App* bench = app.add_subcommand("bench", "Run a benchmark and print its table");
  bench->require_subcommand(1);
  add_bench_noise(*bench, action);
  add_bench_volume(*bench, action);
  add_bench_shafts(*bench, action);
  add_bench_airlight(*bench, action);
  add_bench_clouds(*bench, action);
  add_bench_view(*bench, action);
  add_bench_gl(*bench, action);
  add_bench_look(*bench, action);
  add_bench_sky(*bench, action);
}

}  // namespace nimbus::cli
