// Interruptible calls, each with its own stop request, and error translation (calls.hpp).
#include "calls.hpp"

#include <tbb/task_arena.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stop_token>
#include <thread>

#include "error_text.hpp"
#include "nimbus/base/cancel.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::python {
namespace {

// One call in flight: shared by the Python thread that waits on it, its worker and the exit
// handler, so that none of them depends on another's stack.
struct Call {
  std::stop_source stop;
  std::function<void()> work;
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr error;
};

// The calls in flight, and whether the interpreter is exiting (then no call starts, and a Python
// thread whose call ended never takes the GIL again: Python would end that thread by unwinding
// its stack, through frames that cannot be unwound).
struct Registry {
  std::mutex m;
  std::condition_variable idle;
  std::set<std::shared_ptr<Call>> calls;
  bool exiting = false;
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: a parked thread may still read it at exit
  return *r;
}

std::shared_ptr<Call> start(const std::function<void()>& work) {
  auto call = std::make_shared<Call>();
  call->work = work;
  {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.m);
    if (r.exiting) throw std::runtime_error("the interpreter is exiting: no new nimbus call starts");
    r.calls.insert(call);
  }
  std::thread([call] {
    const StopScope scope(call->stop.get_token());
    try {
      // Isolated: while this thread waits inside its own parallel loops it takes no task of
      // another call's, so every task it runs belongs to this call (cancel.hpp).
      tbb::this_task_arena::isolate([&] { call->work(); });
    } catch (...) {
      call->error = std::current_exception();
    }
    {
      const std::lock_guard<std::mutex> lock(call->m);
      call->finished = true;
    }
    call->cv.notify_all();
    Registry& r = registry();
    {
      const std::lock_guard<std::mutex> lock(r.m);
      r.calls.erase(call);
    }
    r.idle.notify_all();
  }).detach();
  return call;
}

// Parks this thread for good (the interpreter is exiting and this thread may not run Python).
[[noreturn]] void park() {
  Registry& r = registry();
  std::unique_lock<std::mutex> lock(r.m);
  while (true) r.idle.wait(lock);
}

// Waits up to one step for the call to finish, the GIL released; true when it has.
bool wait_step(Call& call, std::chrono::duration<double> step) {
  PyThreadState* state = PyEval_SaveThread();
  bool done;
  {
    std::unique_lock<std::mutex> lock(call.m);
    done = call.cv.wait_for(lock, step, [&] { return call.finished; });
  }
  {
    Registry& r = registry();
    std::unique_lock<std::mutex> lock(r.m);
    if (r.exiting) {
      lock.unlock();
      park();
    }
  }
  PyEval_RestoreThread(state);
  return done;
}

void on_exit() {
  Registry& r = registry();
  PyThreadState* state = PyEval_SaveThread();
  {
    std::unique_lock<std::mutex> lock(r.m);
    r.exiting = true;
    for (const auto& call : r.calls) call->stop.request_stop();
    r.idle.wait(lock, [&] { return r.calls.empty(); });
  }
  PyEval_RestoreThread(state);
}

}  // namespace

void run_interruptible(const std::function<void()>& work, const py::object& progress,
                       const std::atomic<double>* fraction) {
  const std::shared_ptr<Call> call = start(work);
  std::optional<py::error_already_set> python_error;  // Ctrl+C, or the progress callable's
  const auto step = std::chrono::duration<double>(kPollSeconds);
  while (!wait_step(*call, step)) {
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (fraction && !progress.is_none()) progress(fraction->load());
    } catch (py::error_already_set& e) {
      python_error.emplace(std::move(e));
      call->stop.request_stop();  // this call's alone
      while (!wait_step(*call, step)) {
      }
      break;
    }
  }
  if (python_error) {
    python_error->restore();
    throw py::error_already_set();
  }
  if (call->error) std::rethrow_exception(call->error);
}

void register_exit_handler() {
  py::module_::import("atexit").attr("register")(py::cpp_function(&on_exit));
}

void register_errors(py::module_&) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {  // py::type_error and kin: pybind11's own translator
      throw;
    } catch (const py::error_already_set&) {
      throw;
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
