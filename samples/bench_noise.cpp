// `nimbus bench noise` (being written).
#include "cli.hpp"

namespace nimbus::cli {
void add_bench_noise(CLI::App& bench, Action& action) {
  CLI::App* cmd = bench.add_subcommand("noise", "ns per sample of every noise kind against libnoise and glm");
  cmd->callback([&action] { action = [] { return 1; }; });
}
}  // namespace nimbus::cli
