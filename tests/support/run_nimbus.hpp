// Runs the nimbus binary under test with arguments and captures its exit code and output.
#pragma once
#include <string>

namespace nimbus::test {

struct RunResult {
  int code;            // exit status, -1 if it did not exit normally
  std::string output;  // stdout and stderr together
};

RunResult run_nimbus(const std::string& args);

}  // namespace nimbus::test
