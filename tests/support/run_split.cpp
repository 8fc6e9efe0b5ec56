// fork and exec of NIMBUS_BINARY with its streams in temporary files (run_split.hpp).
#include "support/run_split.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

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
  // The safety net on memory: a 4 GiB address-space limit. AddressSanitizer reserves terabytes of
  // address space for its shadow at start and cannot run under it, so a sanitized build bounds
  // single allocations instead (malloc returns null past it; operator new aborts: sanitizer.hpp).
#if defined(__SANITIZE_ADDRESS__)
  constexpr bool kLimitAddressSpace = false;
  const char* asan = std::getenv("ASAN_OPTIONS");
  std::string asan_options = "ASAN_OPTIONS=" + std::string(asan ? asan : "") +
                             ":max_allocation_size_mb=4096:allocator_may_return_null=1";
#else
  constexpr bool kLimitAddressSpace = true;
  std::string asan_options;
#endif
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (asan_options.empty() || std::string(*e).rfind("ASAN_OPTIONS=", 0) != 0) env_text.emplace_back(*e);
  if (!asan_options.empty()) env_text.push_back(asan_options);
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int in_fd = ::open(stdin_path.c_str(), O_RDONLY);
    if (in_fd < 0) ::_exit(126);
    ::dup2(in_fd, 0);
    ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    if (kLimitAddressSpace) {
      const rlimit memory{rlim_t{4} << 30, rlim_t{4} << 30};
      ::setrlimit(RLIMIT_AS, &memory);
    }
    ::alarm(limit_s);  // kept across exec
    ::execve(argv[0], argv.data(), envp.data());
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
