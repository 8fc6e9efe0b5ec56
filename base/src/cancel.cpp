// The process's stop request (cancel.hpp): one atomic flag.
#include "nimbus/base/cancel.hpp"

#include <atomic>

namespace nimbus {
namespace {
std::atomic<bool> g_cancel{false};
}  // namespace

void request_cancel() { g_cancel.store(true, std::memory_order_relaxed); }
void clear_cancel() { g_cancel.store(false, std::memory_order_relaxed); }
bool cancel_requested() { return g_cancel.load(std::memory_order_relaxed); }
void throw_if_cancelled() {
  if (cancel_requested()) throw Cancelled();
}

}  // namespace nimbus
