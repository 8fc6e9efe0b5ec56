// A request to stop long work early (the Python module's Ctrl+C). Loops that run for seconds
// (generation, the light volume, the CPU renderers) poll it between blocks of work and throw
// Cancelled; the nimbus program never asks, so for it the polls are one relaxed load each.
#pragma once
#include <stdexcept>

namespace nimbus {

// Thrown by throw_if_cancelled() once a stop was requested; its message says so in one line.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("stopped at the caller's request (interrupted)") {}
};

// Ask every poll in this process to throw (any thread may call it), and withdraw the request.
// The request stays until withdrawn: the caller that asked withdraws it once its work has ended.
void request_cancel();
void clear_cancel();
bool cancel_requested();

// Throws Cancelled when a stop was requested.
void throw_if_cancelled();

}  // namespace nimbus
