// Runs commands (the nimbus binary under test, or tools such as vdb_print) and captures their
// exit code and output.
#pragma once
#include <string>

namespace nimbus::test {

struct RunResult {
  int code;            // exit status, -1 if it did not exit normally
  std::string output;  // stdout and stderr together
};

// Runs a shell command line with stderr folded into stdout.
RunResult run_command(const std::string& command);

// Runs the nimbus binary under test with `args`.
RunResult run_nimbus(const std::string& args);

}  // namespace nimbus::test
