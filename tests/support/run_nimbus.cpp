// popen() of NIMBUS_BINARY with the output of both streams.
#include "support/run_nimbus.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>

namespace nimbus::test {

RunResult run_nimbus(const std::string& args) {
  const std::string cmd = std::string(NIMBUS_BINARY) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, ""};
  std::string out;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace nimbus::test
