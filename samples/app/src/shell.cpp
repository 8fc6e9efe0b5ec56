// popen() of a command line with both output streams (shell.hpp).
#include "nimbus/app/shell.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <stdexcept>

namespace nimbus::app {

ShellResult run_shell(const std::string& line) {
  FILE* pipe = ::popen((line + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot start a shell for: " + line.substr(0, 300));
  ShellResult r;
  char buf[4096];
  while (const std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) r.output.append(buf, n);
  const int status = ::pclose(pipe);
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (status != -1 && WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

std::string shell_quote(const std::string& text) {
  std::string q = "'";
  for (const char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace nimbus::app
