// The nimbus binary under test and other programs, run through the app library's shell runner.
#include "support/run_nimbus.hpp"

#include <stdexcept>

#include "nimbus/app/shell.hpp"

namespace nimbus::test {

RunResult run_nimbus(const std::string& args) { return run_command(std::string(NIMBUS_BINARY) + " " + args); }

RunResult run_command(const std::string& command) {
  try {
    const app::ShellResult r = app::run_shell(command);
    return {r.exit_code, r.output};
  } catch (const std::runtime_error&) {
    return {-1, ""};
  }
}

}  // namespace nimbus::test
