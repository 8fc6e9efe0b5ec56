// The program's side of an isolated call (isolated_call.hpp): it lowers its own address-space
// limit once started (so that what the loader and the libraries mapped does not count against
// the budget, and a sanitizer's shadow memory is already reserved), does the work and writes the
// status byte and the answer to descriptor 3.
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

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

// A failed operator new ends the program at once, reported as the memory limit it met: unwinding
// from it would run destructors that allocate (OpenVDB's tree clean-up starts TBB tasks), and a
// second bad_alloc inside a destructor is std::terminate, read as a crash on a damaged file.
void out_of_memory() {
  const char status = kNoMemory;
  _exit(write_all(kAnswerFd, &status, 1) ? 0 : 4);
}

}  // namespace

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
  // The budget comes on top of what is mapped now and of the main thread's stack, which grows
  // on demand within RLIMIT_STACK: were it counted in the budget, a small budget would end
  // the program with SIGSEGV at the first deep call, read as a damaged file.
  rlimit stack{};
  const uint64_t stack_room = getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur != RLIM_INFINITY
                                  ? std::min<uint64_t>(stack.rlim_cur, uint64_t(64) << 20)
                                  : uint64_t(64) << 20;
  uint64_t wanted = address_space_in_use() + stack_room + memory;
  if (as.rlim_max != RLIM_INFINITY && as.rlim_max < wanted) wanted = as.rlim_max;  // only ever lowered
  if (as.rlim_cur == RLIM_INFINITY || as.rlim_cur > wanted) {
    as.rlim_cur = wanted;
    if (setrlimit(RLIMIT_AS, &as) != 0) _exit(5);
  }

  std::set_new_handler(out_of_memory);

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
