// Available-memory checks for large grids.
#include "nimbus/base/memory.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace nimbus {

uint64_t available_memory_bytes() {
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

}  // namespace nimbus
