// Running a command line through /bin/sh and quoting words for it: the one place the program,
// its benches (vdb_render, sbatch) and the tests start another program.
#pragma once
#include <string>

namespace nimbus::app {

struct ShellResult {
  int exit_code = -1;  // the exit status; -1 when the command did not exit by itself
  int signal = 0;      // the signal that ended it, 0 when it exited
  std::string output;  // stdout and stderr together
};

// Runs `line` with /bin/sh, stderr folded into stdout, and waits for it. std::runtime_error naming
// the line when no shell could be started.
ShellResult run_shell(const std::string& line);

// `text` single-quoted for a POSIX shell: any bytes, quotes included, reach the program as one word.
std::string shell_quote(const std::string& text);

}  // namespace nimbus::app
