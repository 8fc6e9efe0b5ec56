// fork and exec of NIMBUS_BINARY with its streams in temporary files (run_split.hpp).
#include "support/run_split.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "support/vdb_fixtures.hpp"

namespace nimbus::test {

SplitResult run_nimbus_split(const std::vector<std::string>& args, const std::string& stdin_path, unsigned limit_s) {
  char out_name[] = "/tmp/nimbus_split_out_XXXXXX";
  char err_name[] = "/tmp/nimbus_split_err_XXXXXX";
  const int out_fd = ::mkstemp(out_name), err_fd = ::mkstemp(err_name);
  if (out_fd < 0 || err_fd < 0) return {-1, "", "mkstemp failed"};
  const char* other = std::getenv("NIMBUS_TEST_BINARY");  // another build, e.g. the code before a fix
  std::vector<std::string> argv_text = {other && *other ? other : NIMBUS_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int in_fd = ::open(stdin_path.c_str(), O_RDONLY);
    if (in_fd < 0) ::_exit(126);
    ::dup2(in_fd, 0);
    ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    const rlimit memory{rlim_t{4} << 30, rlim_t{4} << 30};
    ::setrlimit(RLIMIT_AS, &memory);
    ::alarm(limit_s);  // kept across exec
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (pid > 0) ::waitpid(pid, &status, 0);
  ::close(out_fd);
  ::close(err_fd);
  SplitResult r{pid > 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_bytes(out_name), read_bytes(err_name)};
  std::filesystem::remove(out_name);
  std::filesystem::remove(err_name);
  return r;
}

}  // namespace nimbus::test
