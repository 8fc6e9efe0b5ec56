// Available-memory checks for large grids.
#include "nimbus/base/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace nimbus {

namespace {

uint64_t machine_available_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  uint64_t kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024ull;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) return uint64_t(pages) * uint64_t(page);
  return std::numeric_limits<uint64_t>::max();
}

// What the process's own address-space limit (ulimit -v, a batch system's) leaves it.
uint64_t address_space_left_bytes() {
  rlimit r{};
  if (getrlimit(RLIMIT_AS, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return std::numeric_limits<uint64_t>::max();
  std::ifstream in("/proc/self/statm");
  uint64_t pages = 0;
  in >> pages;
  const uint64_t used = pages * uint64_t(sysconf(_SC_PAGE_SIZE));
  return r.rlim_cur > used ? uint64_t(r.rlim_cur) - used : 0;
}

}  // namespace

uint64_t available_memory_bytes() { return std::min(machine_available_bytes(), address_space_left_bytes()); }

void ensure_fits_in_memory(uint64_t count, uint64_t bytes_per_element, const std::string& what) {
  if (bytes_per_element != 0 && count > std::numeric_limits<uint64_t>::max() / bytes_per_element)
    throw OutOfMemoryRequest(what + ": size overflows");
  const uint64_t bytes = count * bytes_per_element;
  const uint64_t avail = available_memory_bytes();
  if (bytes > avail / 10 * 8) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s needs %.1f GiB, more than the %.1f GiB of memory available",
                  what.c_str(), double(bytes) / (1ull << 30), double(avail) / (1ull << 30));
    throw OutOfMemoryRequest(buf);
  }
}

uint64_t peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace nimbus
