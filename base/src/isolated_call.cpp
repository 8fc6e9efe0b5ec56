// A forked, rlimited child for untrusted parsing (isolated_call.hpp). The answer travels through
// an anonymous memory file (memfd): the child writes it whole and exits, the parent reads it
// after waitpid, so neither side waits on the other's pipe.
#include "nimbus/base/isolated_call.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>

#include "nimbus/base/memory.hpp"

namespace nimbus {
namespace {

// Status byte that starts the child's memory file.
constexpr char kAnswer = 'K', kError = 'E', kNoMemory = 'M';

uint64_t address_space_in_use() {
  std::ifstream in("/proc/self/statm");
  uint64_t pages = 0;
  in >> pages;
  return pages * uint64_t(sysconf(_SC_PAGE_SIZE));
}

bool write_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= size_t(n);
  }
  return true;
}

[[noreturn]] void run_child(int fd, const IsolationLimits& limits, uint64_t address_space,
                            const std::function<void(std::string&)>& work) {
  // Quiet: the parent prints the one error line. OpenVDB's warnings would add more.
  const int null = open("/dev/null", O_WRONLY);
  if (null >= 0) {
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
  }
  // Only ever lowered: a limit the process inherited (ulimit, a batch system) stays in force.
  const auto lower = [](int resource, rlim_t value) {
    rlimit r{};
    if (getrlimit(resource, &r) != 0) return false;
    if (r.rlim_max != RLIM_INFINITY && r.rlim_max < value) value = r.rlim_max;
    if (r.rlim_cur != RLIM_INFINITY && r.rlim_cur < value) value = r.rlim_cur;
    r.rlim_cur = value;
    return setrlimit(resource, &r) == 0;
  };
  if (!lower(RLIMIT_AS, address_space + limits.memory_bytes) || !lower(RLIMIT_FSIZE, limits.memory_bytes + 4096) ||
      !lower(RLIMIT_CPU, rlim_t(std::ceil(limits.seconds)) + 1))
    _exit(5);
  itimerval timer{};
  timer.it_value.tv_sec = time_t(limits.seconds);
  timer.it_value.tv_usec = suseconds_t((limits.seconds - std::floor(limits.seconds)) * 1e6);
  if (timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
  // A crash ends the child plainly, for the parent to report: crash handlers inherited from the
  // parent (a sanitizer's, a fuzzer's that saves the input as a "finding") must not run here.
  for (const int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGTRAP}) signal(sig, SIG_DFL);
  signal(SIGALRM, SIG_DFL);
  signal(SIGXCPU, SIG_DFL);
  signal(SIGXFSZ, SIG_DFL);
  setitimer(ITIMER_REAL, &timer, nullptr);

  std::string answer, error;
  char status = kAnswer;
  try {
    work(answer);
  } catch (const std::bad_alloc&) {
    status = kNoMemory;
  } catch (const std::exception& e) {
    status = kError;
    error = e.what();
  } catch (...) {
    status = kError;
    error = "unknown error";
  }
  if (status != kAnswer) answer = std::string();
  const std::string& body = status == kError ? error : answer;
  _exit(write_all(fd, &status, 1) && write_all(fd, body.data(), body.size()) ? 0 : 4);
}

std::string gib(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2g GiB", double(bytes) / double(uint64_t(1) << 30));
  return buf;
}

}  // namespace

uint64_t isolation_memory_for_file(uint64_t file_bytes) {
  const uint64_t big = uint64_t(2) << 30;
  const uint64_t want = file_bytes > (uint64_t(1) << 56) ? UINT64_MAX : std::max(big, 64 * file_bytes);
  return std::max(uint64_t(256) << 20, std::min(want, available_memory_bytes() / 3));
}

std::string call_isolated(const IsolationLimits& limits, const std::function<void(std::string& answer)>& work) {
  if (!(limits.seconds > 0.0 && limits.seconds < 1e7) || limits.memory_bytes == 0)
    throw std::invalid_argument("isolated call: the limits must be > 0");
  const int fd = memfd_create("nimbus-isolated-answer", MFD_CLOEXEC);
  if (fd < 0) throw std::runtime_error(std::string("cannot create the reader's memory file: ") + std::strerror(errno));
  const uint64_t address_space = address_space_in_use();
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) {
    const int err = errno;
    close(fd);
    throw std::runtime_error(std::string("cannot start the reader's process: ") + std::strerror(err));
  }
  if (pid == 0) run_child(fd, limits, address_space, work);

  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0)
    if (errno != EINTR) {
      close(fd);
      throw std::runtime_error(std::string("lost the reader's process: ") + std::strerror(errno));
    }
  std::string bytes;
  struct stat st {};
  if (fstat(fd, &st) == 0 && st.st_size > 0) {
    bytes.resize(size_t(st.st_size));
    size_t got = 0;
    while (got < bytes.size()) {
      const ssize_t n = pread(fd, bytes.data() + got, bytes.size() - got, off_t(got));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += size_t(n);
    }
    bytes.resize(got);
  }
  close(fd);

  using R = IsolatedCallFailed::Reason;
  const std::string limit_text = " (the reader's limits: " + gib(limits.memory_bytes) + ", " +
                                 std::to_string(int(std::ceil(limits.seconds))) + " s)";
  if (WIFSIGNALED(wstatus)) {
    const int sig = WTERMSIG(wstatus);
    if (sig == SIGALRM || sig == SIGXCPU)
      throw IsolatedCallFailed(R::TimedOut, "reading it took too long" + limit_text);
    if (sig == SIGXFSZ) throw IsolatedCallFailed(R::OutOfMemory, "what it holds is too large" + limit_text);
    const char* name = sigabbrev_np(sig);
    throw IsolatedCallFailed(R::Crashed, std::string("the reader crashed on it (SIG") + (name ? name : "?") +
                                             "): the file is damaged or not what it claims to be");
  }
  const int code = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1;
  if (code != 0 || bytes.empty())
    throw IsolatedCallFailed(R::Crashed, "the reader failed on it (exit code " + std::to_string(code) +
                                             "): the file is damaged or not what it claims to be");
  if (bytes[0] == kNoMemory) throw IsolatedCallFailed(R::OutOfMemory, "reading it needs more memory" + limit_text);
  if (bytes[0] == kError) throw IsolatedCallFailed(R::ChildError, bytes.substr(1));
  if (bytes[0] != kAnswer) throw IsolatedCallFailed(R::Crashed, "the reader's answer is malformed");
  bytes.erase(0, 1);
  return bytes;
}

}  // namespace nimbus
