// Running untrusted parsing in a child process with a memory and time limit, so that nothing the
// input holds (a crash in a third-party reader, an absurd allocation, an endless loop) can crash,
// hang or exhaust the caller. The child writes its answer as bytes; the caller gets them back,
// or an IsolatedCallFailed that says what went wrong.
#pragma once
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace nimbus {

struct IsolationLimits {
  uint64_t memory_bytes = uint64_t(2) << 30;  // the child's new address space, and its answer's size
  double seconds = 300.0;                     // wall-clock time (and CPU time) the child may take
};

// The child did not answer: it was killed by a signal, ran out of time or memory, or its answer
// was too large. `what()` is one line of plain words (no file name: the caller adds it).
struct IsolatedCallFailed : std::runtime_error {
  enum class Reason { Crashed, TimedOut, OutOfMemory, ChildError };
  Reason reason;
  IsolatedCallFailed(Reason r, const std::string& message) : std::runtime_error(message), reason(r) {}
};

// Forks; in the child sets the limits (RLIMIT_AS: the address space in use now + memory_bytes;
// RLIMIT_FSIZE: memory_bytes; alarm and RLIMIT_CPU: seconds), sends its stdout and stderr to
// /dev/null and calls work(answer), whose bytes are handed back. std::bad_alloc in the child is
// reported as OutOfMemory; any other exception escaping `work` as ChildError with its message.
// The child runs no destructors or atexit handlers of the parent (it ends with _exit). `work`
// must not use threads: only the forking thread exists in the child.
std::string call_isolated(const IsolationLimits& limits, const std::function<void(std::string& answer)>& work);

// The automatic memory budget for parsing a file of `file_bytes`: max(2 GiB, 64 x its size),
// at most a third of the memory available now, at least 256 MiB.
uint64_t isolation_memory_for_file(uint64_t file_bytes);

}  // namespace nimbus
