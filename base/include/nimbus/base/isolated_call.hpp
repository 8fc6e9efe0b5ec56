// Running untrusted parsing in a separate program with a memory and time limit, so that nothing
// the input holds (a crash in a third-party reader, an absurd allocation, an endless loop) can
// crash, hang or exhaust the caller. The program writes its answer as bytes; the caller gets them
// back, or an IsolatedCallFailed that says what went wrong.
//
// The program is started fresh (fork, then exec at once), never run as a forked copy of the
// caller: a copy inherits every lock another thread of the caller held at that moment (OpenVDB's
// registries, a sanitizer's allocator) and can wait for it for ever.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace nimbus {

struct IsolationLimits {
  uint64_t memory_bytes = uint64_t(2) << 30;  // address space beyond the program's own at start, and its answer's size
  double seconds = 300.0;                     // wall-clock time (and CPU time) the program may take, start-up included
};

// The program did not answer: it was killed by a signal, ran out of time or memory, its answer
// was too large, or it reported an error. `what()` is one line of plain words (no file name: the
// caller adds it).
struct IsolatedCallFailed : std::runtime_error {
  enum class Reason { Crashed, TimedOut, OutOfMemory, ChildError };
  Reason reason;
  IsolatedCallFailed(Reason r, const std::string& message) : std::runtime_error(message), reason(r) {}
};

// The caller's side. Starts `program` with `args` and waits for it. Between fork and exec the
// child only makes system calls: stdin, stdout and stderr to /dev/null, the answer file as
// descriptor 3 and every other descriptor closed, the signal mask emptied, limits lowered
// (RLIMIT_CPU: seconds, RLIMIT_FSIZE: memory_bytes, no core files) and a timer of `seconds`
// set. The program, once started, lowers its own RLIMIT_AS (serve_isolated_call).
// Limits are only ever lowered: an inherited one (ulimit, a batch system) stays in force.
// std::runtime_error (not IsolatedCallFailed) when the program cannot be started at all.
std::string call_isolated(const IsolationLimits& limits, const std::filesystem::path& program,
                          const std::vector<std::string>& args);

// The program's side: its main() returns serve_isolated_call(argc, argv, work). Lowers RLIMIT_AS
// to what is mapped now (1 MiB of stack grown first) + the caller's memory_bytes, calls
// work(args, answer) and hands the answer back. A failed operator new ends the program at once and
// is reported as OutOfMemory (so is a std::bad_alloc thrown otherwise); any other exception as
// ChildError with its message. Run by hand (not by call_isolated), it says so on stderr and
// returns 2.
int serve_isolated_call(int argc, char** argv,
                        const std::function<void(const std::vector<std::string>& args, std::string& answer)>& work);

// The automatic memory budget for parsing a file of `file_bytes`: max(2 GiB, 64 x its size),
// at most a third of the memory available now, at least 256 MiB.
uint64_t isolation_memory_for_file(uint64_t file_bytes);

}  // namespace nimbus
