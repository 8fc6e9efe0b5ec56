// Interruptible calls and error translation (calls.hpp).
#include "calls.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "error_text.hpp"
#include "nimbus/base/cancel.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::python {

void run_interruptible(const std::function<void()>& work, const py::object& progress,
                       const std::atomic<double>* fraction) {
  std::exception_ptr error;
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  std::thread worker;
  {
    py::gil_scoped_release release;
    worker = std::thread([&] {
      try {
        work();
      } catch (...) {
        error = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(m);
        finished = true;
      }
      cv.notify_all();
    });
  }
  std::optional<py::error_already_set> python_error;  // Ctrl+C, or the progress callable's
  const auto step = std::chrono::duration<double>(kPollSeconds);
  while (true) {
    bool done;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(m);
      done = cv.wait_for(lock, step, [&] { return finished; });
    }
    if (done) break;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (fraction && !progress.is_none()) progress(fraction->load());
    } catch (py::error_already_set& e) {
      python_error.emplace(std::move(e));
      request_cancel();
      break;
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (python_error) {
    clear_cancel();
    python_error->restore();
    throw py::error_already_set();
  }
  if (error) std::rethrow_exception(error);
}

void register_errors(py::module_&) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const volume::GridNotFound& e) {  // the program's usage error (--grid)
      PyErr_SetString(PyExc_ValueError, cli::one_line(e.what()).c_str());
    } catch (const Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const std::invalid_argument& e) {  // UsageError, OutOfMemoryRequest, bad parameters
      PyErr_SetString(PyExc_ValueError, cli::one_line(e.what()).c_str());
    } catch (const std::filesystem::filesystem_error& e) {
      PyErr_SetString(PyExc_OSError, cli::one_line(e.what()).c_str());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    } catch (const std::exception& e) {
      PyErr_SetString(PyExc_RuntimeError, cli::one_line(e.what()).c_str());
    }
  });
}

}  // namespace nimbus::python
