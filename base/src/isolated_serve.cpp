// The program's side of an isolated call (isolated_call.hpp): it lowers its own address-space
// limit once started (so that what the loader and the libraries mapped does not count against
// the budget, and a sanitizer's shadow memory is already reserved; the budget is then exactly
// how much more the program may map), does the work and writes the
// status byte and the answer to descriptor 3.
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <alloca.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>

#include "isolated_protocol.hpp"
#include "nimbus/base/isolated_call.hpp"

namespace nimbus {
namespace {

using namespace isolated;

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

// Touches `bytes` of the stack below this frame, so that the stack's mapping has grown by then.
[[gnu::noinline]] void grow_stack(size_t bytes) {
  volatile char* below = static_cast<volatile char*>(alloca(bytes));
  for (size_t i = 0; i < bytes; i += 4096) below[i] = 0;
  below[bytes - 1] = 0;
}

// A failed operator new ends the program at once, reported as the memory limit it met: unwinding
// from it would run destructors that allocate (OpenVDB's tree clean-up starts TBB tasks), and a
// second bad_alloc inside a destructor is std::terminate, read as a crash on a damaged file.
void out_of_memory() {
  const char status = kNoMemory;
  _exit(write_all(kAnswerFd, &status, 1) ? 0 : 4);
}

#if !defined(__SANITIZE_ADDRESS__)
// C libraries under the budget do not all check malloc (Blosc prints "Error allocating memory!"
// and decompresses into NULL). A crash after a failed allocation is the budget running out, not
// a damaged file, and is reported as such. (Under AddressSanitizer its own allocator and crash
// reports take this place.)
volatile sig_atomic_t allocation_failed = 0;

void after_crash(int sig) {
  if (!allocation_failed) {
    raise(sig);  // SA_RESETHAND restored the default action: the crash it is
    return;
  }
  const char status = kNoMemory;
  _exit(write(kAnswerFd, &status, 1) == 1 ? 0 : 4);
}

void report_crashes_after_failed_allocations() {
  static char alternate[64 << 10];  // a crash may come from the stack itself
  stack_t st{};
  st.ss_sp = alternate;
  st.ss_size = sizeof alternate;
  sigaltstack(&st, nullptr);
  struct sigaction sa {};
  sa.sa_handler = after_crash;
  sa.sa_flags = SA_ONSTACK | SA_RESETHAND;
  for (const int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) sigaction(sig, &sa, nullptr);
}
#else
void report_crashes_after_failed_allocations() {}
#endif

}  // namespace
}  // namespace nimbus

#if !defined(__SANITIZE_ADDRESS__)
// The programs that serve isolated calls (this object is linked only into them) see every failed
// malloc: glibc's own allocator, called under its exported names.
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* malloc(size_t n) {
  void* p = __libc_malloc(n);
  if (!p) nimbus::allocation_failed = 1;
  return p;
}
void* calloc(size_t n, size_t size) {
  void* p = __libc_calloc(n, size);
  if (!p && n && size) nimbus::allocation_failed = 1;
  return p;
}
void* realloc(void* old, size_t n) {
  void* p = __libc_realloc(old, n);
  if (!p && n) nimbus::allocation_failed = 1;
  return p;
}
}
#endif

namespace nimbus {

int serve_isolated_call(int argc, char** argv,
                        const std::function<void(const std::vector<std::string>& args, std::string& answer)>& work) {
  struct stat answer_file {};
  char* end = nullptr;
  const unsigned long long memory = argc >= 3 ? std::strtoull(argv[2], &end, 10) : 0;
  if (argc < 3 || std::strcmp(argv[1], kMarker) != 0 || !end || *end != '\0' || memory == 0 ||
      fstat(kAnswerFd, &answer_file) != 0) {
    std::fprintf(stderr, "%s: this program reads untrusted files for nimbus, in a process of their own; nimbus "
                 "starts it, with its limits, not a person\n", argc > 0 ? argv[0] : "nimbus reader");
    return 2;
  }
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) != 0) _exit(5);
  // The budget comes on top of what is mapped now, the main thread's stack grown to 1 MiB first:
  // a stack that had to grow into the budget would end the program with SIGSEGV at the first deep
  // call once the heap had taken the budget, read as a damaged file.
  grow_stack(size_t(1) << 20);
  uint64_t wanted = address_space_in_use() + memory;
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's own report needs memory (its symbolizer maps module lists): at an exhausted
  // limit GCC 12's libasan fails that mmap inside its report and waits on its own lock for ever.
  wanted += uint64_t(256) << 20;
#endif
  if (as.rlim_max != RLIM_INFINITY && as.rlim_max < wanted) wanted = as.rlim_max;  // only ever lowered
  if (as.rlim_cur == RLIM_INFINITY || as.rlim_cur > wanted) {
    as.rlim_cur = wanted;
    if (setrlimit(RLIMIT_AS, &as) != 0) _exit(5);
  }

  std::set_new_handler(out_of_memory);
  report_crashes_after_failed_allocations();

  std::string answer, error;
  char status = kAnswer;
  try {
    work(std::vector<std::string>(argv + 3, argv + argc), answer);
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
  // _exit: no static destructors of the libraries the work used; the answer is all that counts.
  _exit(write_all(kAnswerFd, &status, 1) && write_all(kAnswerFd, body.data(), body.size()) ? 0 : 4);
}

}  // namespace nimbus
