// How the module calls nimbus: long work on a thread of its own with the GIL released, stopped by
// Ctrl+C (KeyboardInterrupt) within a poll; nimbus's errors as Python's, in the program's words.
#pragma once
#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>

namespace nimbus::python {

namespace py = pybind11;

// Runs `work` on a worker thread while this thread, the GIL released, waits in steps of
// kPollSeconds. At each step it checks Python's signals: a KeyboardInterrupt asks the work to
// stop (nimbus/base/cancel.hpp: the loops of generation and rendering poll it), waits for it to
// end and is raised. When `progress` is a callable and `fraction` is given, it is called at each
// step with the fraction of the work done; an exception it raises stops the work the same way.
// An exception the work throws is rethrown here (and translated, register_errors).
inline constexpr double kPollSeconds = 0.05;
void run_interruptible(const std::function<void()>& work, const py::object& progress = py::none(),
                       const std::atomic<double>* fraction = nullptr);

// Translates nimbus's exceptions: bad arguments (nimbus's UsageError, std::invalid_argument,
// a request too large for memory, an unknown grid) -> ValueError; file-system errors -> OSError; a stop ->
// KeyboardInterrupt; other runtime errors -> RuntimeError; each message one line (error_text.hpp).
void register_errors(py::module_& m);

}  // namespace nimbus::python
