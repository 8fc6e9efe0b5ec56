// popen() of NIMBUS_BINARY with the output of both streams.
#include "support/run_nimbus.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>

namespace nimbus::test {

RunResult run_nimbus(const std::string& args) { return run_command(std::string(NIMBUS_BINARY) + " " + args); }

RunResult run_command(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, ""};
  std::string out;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace nimbus::test
