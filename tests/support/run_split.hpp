// Runs the nimbus binary under test without a shell: arguments passed as they are (an empty one
// stays empty), stdin from a file, stdout and stderr captured apart.
#pragma once
#include <string>
#include <vector>

namespace nimbus::test {

struct SplitResult {
  int code;  // exit status; -1 when it did not exit normally (a crash, or the safety limit)
  std::string out, err;
};

// Runs NIMBUS_BINARY (or the environment's NIMBUS_TEST_BINARY, to check that a test fails on
// the code before a fix) with `args`, stdin read from `stdin_path`. A run that would run away is
// ended after `limit_s` seconds (SIGALRM) or when it maps more than 4 GiB: a safety net for the
// hostile cases, never an assertion on time.
SplitResult run_nimbus_split(const std::vector<std::string>& args, const std::string& stdin_path = "/dev/null",
                             unsigned limit_s = 60);

}  // namespace nimbus::test
