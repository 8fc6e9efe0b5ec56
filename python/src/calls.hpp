// How the module calls nimbus: long work on a thread of its own with the GIL released, stopped by
// its own stop request (Ctrl+C on the main thread, an exception in its progress callable, the
// interpreter's exit); nimbus's errors as Python's, in one line.
#pragma once
#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>

namespace nimbus::python {

namespace py = pybind11;

// Runs `work` on a worker thread of its own while this thread, the GIL released, waits in steps
// of kPollSeconds. The call has a stop source of its own (nimbus/base/cancel.hpp), installed on
// the worker, whose TBB work is isolated from other calls' (a thread waiting on this call's work
// runs no task of another call's). At each step this thread checks Python's signals: a
// KeyboardInterrupt (delivered to the main thread only) stops this call alone, waits for its work
// to end and is raised. When `progress` is a callable and `fraction` is given, it is called at
// each step with the fraction done; an exception it raises stops this call the same way. An
// exception the work throws is rethrown here (and translated, register_errors).
// At the interpreter's exit (an atexit handler, before Python finalizes), every call still in
// flight, in any thread (a daemon thread's), is stopped and waited for; a call started after that
// raises RuntimeError.
inline constexpr double kPollSeconds = 0.05;
void run_interruptible(const std::function<void()>& work, const py::object& progress = py::none(),
                       const std::atomic<double>* fraction = nullptr);

// Registers the exit handler above with Python's atexit.
void register_exit_handler();

// Translates nimbus's exceptions: bad arguments (nimbus's UsageError, std::invalid_argument,
// a request too large for memory, an unknown grid) -> ValueError; file-system errors -> OSError; a stop ->
// KeyboardInterrupt; other runtime errors -> RuntimeError; each message one line (error_text.hpp).
void register_errors(py::module_& m);

}  // namespace nimbus::python
