// Corpus replay without libFuzzer: runs a harness's LLVMFuzzerTestOneInput once on every file
// given (directories are walked, in sorted order), each in its own child process with a memory
// limit and a time limit, and reports every input that crashed, aborted (a broken contract, see
// fuzz_common.hpp), ran out of its memory or time, or whose peak resident memory passed --rss-mb
// (as libFuzzer's -rss_limit_mb: a file of a few KB must not cost gigabytes, even when the
// allocation succeeds). Exit status 0 only when every input passed.
//
//   nimbus_fuzz_<target>_replay [--mem-mb N] [--rss-mb N] [--cpu-s N] [--timeout S] PATH...
//
// --mem-mb (default 4096) limits the address space (RLIMIT_AS); --rss-mb (default 2048) is
// checked on the child's peak resident set after the input ran; --cpu-s (default 20) limits the
// CPU time (RLIMIT_CPU: SIGXCPU), which a corpus input needs a few milliseconds of, so only a
// spinning reader reaches it, however loaded the machine; --timeout (default 600) is a last
// wall-clock guard (SIGALRM) for a child blocked without using CPU.
//
// The parent never calls the code under test, so it forks before OpenVDB or TBB start threads.
// The harnesses' scratch files go to a temporary directory of the parent's (NIMBUS_FUZZ_TMPDIR).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

int usage(const char* why) {
  std::fprintf(stderr, "replay: %s (usage: replay [--mem-mb N] [--rss-mb N] [--cpu-s N] [--timeout SECONDS] FILE_OR_DIR...)\n", why);
  return 2;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

constexpr int kRssExit = 86;  // the child's exit status when its peak resident memory passed --rss-mb

// Soft limits only: the code under test may fork a reader that sets limits of its own, and one
// above a hard limit inherited from here would fail (EPERM) for reasons that are not the input's.
void soft_limit(int resource, rlim_t value) {
  rlimit limit{};
  getrlimit(resource, &limit);
  limit.rlim_cur = limit.rlim_max == RLIM_INFINITY ? value : std::min(value, limit.rlim_max);
  setrlimit(resource, &limit);
}

[[noreturn]] void run_child(const fs::path& input, long mem_mb, long rss_mb, long cpu_s, long timeout_s) {
  // ASan's shadow memory needs terabytes of address space.
  if (mem_mb > 0 && !kAddressSanitizer) soft_limit(RLIMIT_AS, rlim_t(mem_mb) << 20);
  soft_limit(RLIMIT_CORE, 0);
  if (cpu_s > 0) soft_limit(RLIMIT_CPU, rlim_t(cpu_s));
  alarm(unsigned(timeout_s));
  std::ifstream in(input, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", input.c_str());
    std::_Exit(3);
  }
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  // Not exit(): a library's exit handler can wait for a thread that only the parent has
  // (log4cplus, loaded with OpenVDB, starts one before main), and hang. The harness's scratch
  // file lies in the parent's temporary directory, removed at the end.
  std::fflush(nullptr);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);  // ru_maxrss in KB
  if (rss_mb > 0 && usage.ru_maxrss / 1024 > rss_mb) {
    std::fprintf(stderr, "replay: %s: peak resident memory %ld MB, over the %ld MB limit\n", input.c_str(),
                 long(usage.ru_maxrss / 1024), rss_mb);
    std::_Exit(kRssExit);
  }
  std::_Exit(0);
}

}  // namespace

int main(int argc, char** argv) {
  long mem_mb = 4096, rss_mb = 2048, cpu_s = 20, timeout_s = 600;
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--mem-mb" || a == "--rss-mb" || a == "--cpu-s" || a == "--timeout") && i + 1 < argc) {
      char* end = nullptr;
      const long v = std::strtol(argv[++i], &end, 10);
      if (*end || v < 0) return usage("a number >= 0 is needed");
      (a == "--mem-mb" ? mem_mb : a == "--rss-mb" ? rss_mb : a == "--cpu-s" ? cpu_s : timeout_s) = v;
    } else if (a.rfind("--", 0) == 0) {
      return usage(("unknown option " + a).c_str());
    } else {
      std::error_code ec;
      if (fs::is_directory(a, ec)) {
        std::vector<fs::path> found;
        for (const auto& e : fs::recursive_directory_iterator(a))
          if (e.is_regular_file() && e.path().filename().string()[0] != '.') found.push_back(e.path());
        std::sort(found.begin(), found.end());
        inputs.insert(inputs.end(), found.begin(), found.end());
      } else if (fs::is_regular_file(a, ec)) {
        inputs.push_back(a);
      } else {
        return usage(("no such file or directory: " + a).c_str());
      }
    }
  }
  if (inputs.empty()) return usage("no inputs (an empty corpus checks nothing)");
  if (timeout_s == 0) timeout_s = 600;

  std::string tmp_template = (fs::temp_directory_path() / "nimbus-fuzz-replay-XXXXXX").string();
  if (!mkdtemp(tmp_template.data())) {
    std::perror("replay: mkdtemp");
    return 1;
  }
  const fs::path tmp_dir = tmp_template;
  setenv("NIMBUS_FUZZ_TMPDIR", tmp_dir.c_str(), 1);

  std::fflush(nullptr);
  int failed = 0;
  for (const fs::path& input : inputs) {
    const pid_t pid = fork();
    if (pid < 0) {
      std::perror("replay: fork");
      return 1;
    }
    if (pid == 0) run_child(input, mem_mb, rss_mb, cpu_s, timeout_s);
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) {
      std::perror("replay: waitpid");
      return 1;
    }
    std::string outcome;
    if (WIFSIGNALED(status)) {
      const int sig = WTERMSIG(status);
      outcome = sig == SIGALRM  ? "still running after " + std::to_string(timeout_s) + " s"
                : sig == SIGXCPU ? "used more than " + std::to_string(cpu_s) + " s of CPU time"
                                 : std::string("killed by signal ") + std::to_string(sig) + " (" + strsignal(sig) + ")";
    } else if (WEXITSTATUS(status) == kRssExit) {
      outcome = "peak resident memory over " + std::to_string(rss_mb) + " MB";
    } else if (WEXITSTATUS(status) != 0) {
      outcome = "exit status " + std::to_string(WEXITSTATUS(status));
    }
    if (!outcome.empty()) {
      ++failed;
      std::printf("FAILED %s: %s\n", input.c_str(), outcome.c_str());
      std::fflush(stdout);
    }
  }
  std::error_code ec;
  fs::remove_all(tmp_dir, ec);
  const std::string space = mem_mb > 0 && !kAddressSanitizer ? std::to_string(mem_mb) + " MB" : "unlimited";
  std::printf("replayed %zu inputs: %zu passed, %d failed (each: address space %s, peak resident %ld MB, "
              "%ld s of CPU)\n", inputs.size(), inputs.size() - size_t(failed), failed, space.c_str(), rss_mb, cpu_s);
  return failed ? 1 : 0;
}
