// A call's stop request. Cancellation belongs to a call, not to the process: whoever runs a call
// that may have to stop early (the Python module, for Ctrl+C or a progress callable that raised)
// owns a std::stop_source and installs its token with a StopScope on the thread that runs the
// call. The loops that run for seconds (generation, noise grids, the light volume, the CPU
// renderers) take that token with current_stop_token() on the calling thread, before they fan
// out to TBB's threads, and poll it between blocks of work (throw_if_stopped). So a loop polls
// its own call's token whichever thread runs its tasks, and a stop reaches no other call.
// The nimbus program installs no token: every poll is then one load of an empty token.
#pragma once
#include <stdexcept>
#include <stop_token>

namespace nimbus {

// Thrown by throw_if_stopped() once its call's stop was requested; one line that says so.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("stopped at the caller's request (interrupted)") {}
};

// The token of the call this thread runs (the innermost StopScope on it), or an empty token that
// never stops. Read it on the call's own thread: a TBB worker thread has none.
std::stop_token current_stop_token();

// Makes `token` the current stop token of this thread for the scope's lifetime (nestable).
class StopScope {
 public:
  explicit StopScope(std::stop_token token);
  ~StopScope();
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  std::stop_token previous_;
};

// Throws Cancelled when a stop of `stop`'s call was requested.
inline void throw_if_stopped(const std::stop_token& stop) {
  if (stop.stop_requested()) throw Cancelled();
}

}  // namespace nimbus
