// Refuse sizes that would exhaust memory before allocating them.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

namespace nimbus {

// Thrown when a request needs more memory than the machine has available.
struct OutOfMemoryRequest : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Bytes of memory available to this process now: MemAvailable (else physical memory), and no
// more than its address-space limit (RLIMIT_AS) leaves it.
uint64_t available_memory_bytes();

// The most resident memory this process has held so far, bytes (getrusage's ru_maxrss).
uint64_t peak_resident_bytes();

// Throws OutOfMemoryRequest naming `what` when `bytes` exceeds 80 % of available memory, or
// when the element count overflows.
void ensure_fits_in_memory(uint64_t count, uint64_t bytes_per_element, const std::string& what);

}  // namespace nimbus
