// The check-only mode of every command that writes (cli.hpp).
#include "cli.hpp"

namespace nimbus::cli {
namespace {
bool g_check_only = false;
}  // namespace

void set_check_only(bool on) { g_check_only = on; }
bool check_only() { return g_check_only; }
void checks_done() {
  if (g_check_only) throw ChecksPassed{};
}

}  // namespace nimbus::cli
