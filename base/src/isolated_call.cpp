// The caller's side of an isolated call (isolated_call.hpp): vfork, then only system calls until
// exec. The answer travels through an anonymous memory file (memfd): the program writes it whole
// and exits, the caller reads it after waitpid, so neither side waits on the other's pipe.
#include "nimbus/base/isolated_call.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "isolated_protocol.hpp"
#include "nimbus/base/memory.hpp"

namespace nimbus {
namespace {

using namespace isolated;

// Lowers a limit, never raises it: a limit the process inherited (ulimit, a batch system) stays.
bool lower(int resource, rlim_t value) {
  rlimit r{};
  if (getrlimit(resource, &r) != 0) return false;
  if (r.rlim_max != RLIM_INFINITY && r.rlim_max < value) value = r.rlim_max;
  if (r.rlim_cur != RLIM_INFINITY && r.rlim_cur < value) value = r.rlim_cur;
  r.rlim_cur = value;
  return setrlimit(resource, &r) == 0;
}

// Reports errno through the answer file and ends the forked child.
[[noreturn]] void not_started(int answer_fd, int err) {
  char text[16];
  int n = 0;
  for (int e = err > 0 ? err : 0; n == 0 || e > 0; e /= 10) text[n++] = char('0' + e % 10);
  const char status = kExecFailed;
  (void)!write(answer_fd, &status, 1);
  while (n > 0) (void)!write(answer_fd, &text[--n], 1);
  _exit(127);
}

// The vforked child: system calls only (the caller's other threads may hold any lock),
// then the program. Anything that fails before exec is reported through the answer file.
[[noreturn]] void start_program(int answer_fd, const char* program, char* const* argv, const IsolationLimits& limits) {
  const auto fail = [&](int err) { not_started(answer_fd, err); };
  // Quiet: the caller prints the one error line. OpenVDB's warnings would add more.
  const int null = open("/dev/null", O_RDWR);
  if (null < 0 || dup2(null, STDIN_FILENO) < 0 || dup2(null, STDOUT_FILENO) < 0 || dup2(null, STDERR_FILENO) < 0)
    fail(errno);
  if (answer_fd == kAnswerFd ? fcntl(answer_fd, F_SETFD, 0) < 0 : dup2(answer_fd, kAnswerFd) < 0) fail(errno);
  answer_fd = kAnswerFd;
  // Nothing else of the caller's reaches the program: files, sockets, pipes.
  if (close_range(kAnswerFd + 1, ~0U, 0) != 0) {
    rlimit files{};
    getrlimit(RLIMIT_NOFILE, &files);
    for (rlim_t fd = kAnswerFd + 1; fd < std::min<rlim_t>(files.rlim_cur, 1 << 20); ++fd) close(int(fd));
  }
  if (!lower(RLIMIT_FSIZE, limits.memory_bytes + 4096) || !lower(RLIMIT_CPU, rlim_t(std::ceil(limits.seconds)) + 1) ||
      !lower(RLIMIT_CORE, 0))
    fail(errno);
  // A crash, the timer and the limits end the program plainly, for the caller to report, even if
  // the caller ignores or blocks these signals (exec keeps both). Raw system calls: the C
  // library's and a sanitizer's wrappers keep state in memory this child shares with the caller.
  struct {
    void (*handler)(int);
    unsigned long flags;
    void (*restorer)();
    unsigned long mask;
  } plain{SIG_DFL, 0, nullptr, 0};
  for (int sig = 1; sig <= 64; ++sig)
    if (sig != SIGKILL && sig != SIGSTOP) syscall(SYS_rt_sigaction, sig, &plain, nullptr, sizeof(unsigned long));
  const unsigned long none = 0;
  syscall(SYS_rt_sigprocmask, SIG_SETMASK, &none, nullptr, sizeof none);
  itimerval timer{};  // kept across exec
  timer.it_value.tv_sec = time_t(limits.seconds);
  timer.it_value.tv_usec = suseconds_t((limits.seconds - std::floor(limits.seconds)) * 1e6);
  if (timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
  if (setitimer(ITIMER_REAL, &timer, nullptr) != 0) fail(errno);
  execv(program, argv);
  not_started(answer_fd, errno);
}

std::string gib(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2g GiB", double(bytes) / double(uint64_t(1) << 30));
  return buf;
}

std::string read_answer(int fd) {
  std::string bytes;
  struct stat st {};
  if (fstat(fd, &st) != 0 || st.st_size <= 0) return bytes;
  bytes.resize(size_t(st.st_size));
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = pread(fd, bytes.data() + got, bytes.size() - got, off_t(got));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += size_t(n);
  }
  bytes.resize(got);
  return bytes;
}

}  // namespace

uint64_t isolation_memory_for_file(uint64_t file_bytes) {
  const uint64_t big = uint64_t(2) << 30;
  const uint64_t want = file_bytes > (uint64_t(1) << 56) ? UINT64_MAX : std::max(big, 64 * file_bytes);
  return std::max(uint64_t(256) << 20, std::min(want, available_memory_bytes() / 3));
}

std::string call_isolated(const IsolationLimits& limits, const std::filesystem::path& program,
                          const std::vector<std::string>& args) {
  if (!(limits.seconds > 0.0 && limits.seconds < 1e7) || limits.memory_bytes == 0)
    throw std::invalid_argument("isolated call: the limits must be > 0");
  // Everything the child needs is made here: after fork it may not allocate.
  std::vector<std::string> words{program.string(), kMarker, std::to_string(limits.memory_bytes)};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  int fd = memfd_create("nimbus-isolated-answer", MFD_CLOEXEC);
  if (fd < 0) throw std::runtime_error(std::string("cannot create the reader's memory file: ") + std::strerror(errno));
  if (fd <= STDERR_FILENO) {  // the child's standard streams must not land on it
    const int moved = fcntl(fd, F_DUPFD_CLOEXEC, kAnswerFd);
    close(fd);
    if (moved < 0) throw std::runtime_error(std::string("cannot place the reader's memory file: ") + std::strerror(errno));
    fd = moved;
  }
  // vfork, not fork: fork runs the libraries' atfork handlers in the child (Blosc's frees
  // memory, and under ASan waited for ever on an allocator lock held by another thread). The
  // caller's signals are blocked until the child has reset its own, so that no handler of the
  // caller runs in the child, whose memory is the caller's until exec.
  sigset_t all, before;
  sigfillset(&all);
  pthread_sigmask(SIG_SETMASK, &all, &before);
  const pid_t pid = vfork();
  if (pid == 0) start_program(fd, words[0].c_str(), argv.data(), limits);
  const int vfork_errno = errno;
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  if (pid < 0) {
    close(fd);
    throw std::runtime_error(std::string("cannot start the reader's process: ") + std::strerror(vfork_errno));
  }

  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0)
    if (errno != EINTR) {
      close(fd);
      throw std::runtime_error(std::string("lost the reader's process: ") + std::strerror(errno));
    }
  std::string bytes = read_answer(fd);
  close(fd);

  using R = IsolatedCallFailed::Reason;
  if (!bytes.empty() && bytes[0] == kExecFailed)
    throw std::runtime_error("cannot start " + program.string() + ": " + std::strerror(std::atoi(bytes.c_str() + 1)));
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
