#include "python/python_run.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <exception>
#include <mutex>
#include <string>

#include "core/cancellation.hpp"

namespace bemshape::python {
namespace {

using Clock = std::chrono::steady_clock;

/// Jobs running in the process. The first to start and the last to end clear the
/// cancellation state, so a Ctrl-C that stopped one call does not stop the next.
std::atomic<int> active_runs{0};

/// Python's SIGINT action while the chain is installed; the chain passes the signal on to it.
struct sigaction python_sigint_action {};
/// Whether the chain is installed (only the main thread installs and removes it).
bool sigint_chained = false;

extern "C" void cancel_then_pass_on(int signal) {
  request_cancellation(signal);
  // Python's own C handler marks the signal as tripped: PyErr_CheckSignals then runs
  // signal.default_int_handler, which raises KeyboardInterrupt.
  if (!(python_sigint_action.sa_flags & SA_SIGINFO) && python_sigint_action.sa_handler != SIG_DFL &&
      python_sigint_action.sa_handler != SIG_IGN)
    python_sigint_action.sa_handler(signal);
}

/// True on the main thread while Python's SIGINT handler is signal.default_int_handler
/// (raise KeyboardInterrupt): then Ctrl-C may stop the job at once. A handler of the user's
/// own is left alone and runs at the next poll.
bool sigint_raises_keyboard_interrupt() {
  const py::module_ threading = py::module_::import("threading");
  if (!threading.attr("current_thread")().is(threading.attr("main_thread")()))
    return false;
  const py::module_ signal = py::module_::import("signal");
  return signal.attr("getsignal")(SIGINT).is(signal.attr("default_int_handler"));
}

}  // namespace

struct PythonRun::State {
  std::mutex mutex;
  py::object progress;  ///< the user's callable or None (touched with the GIL held only)
  std::string stage;
  Clock::time_point last_poll{};
  std::optional<py::error_already_set> error;  ///< what cancelled the job, if Python raised
};

PythonRun::PythonRun(std::optional<int> threads, py::object progress)
    : state_(std::make_shared<State>()), previous_threads_(omp_get_max_threads()) {
  if (threads && *threads <= 0)
    throw InputError("threads must be a positive number, got " + std::to_string(*threads));
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw InputError("progress must be a callable progress(stage, fraction) or None");
  state_->progress = std::move(progress);
  const bool chain = !sigint_chained && sigint_raises_keyboard_interrupt();
  // Nothing below throws: the destructor undoes it all.
  if (active_runs++ == 0)
    clear_cancellation();
  if (chain) {
    struct sigaction chain {};
    chain.sa_handler = cancel_then_pass_on;
    sigemptyset(&chain.sa_mask);
    chain.sa_flags = SA_ONSTACK;  // as Python installs its own
    if (sigaction(SIGINT, &chain, &python_sigint_action) == 0)
      sigint_chained = sigint_chained_ = true;
  }
  if (threads)
    omp_set_num_threads(*threads);
}

PythonRun::~PythonRun() {
  omp_set_num_threads(previous_threads_);
  if (sigint_chained_) {
    sigaction(SIGINT, &python_sigint_action, nullptr);
    sigint_chained = false;
  }
  if (--active_runs == 0)
    clear_cancellation();
}

int PythonRun::threads() const {
  return omp_get_max_threads();
}

ProgressCallback PythonRun::callback() {
  // A plain pointer: the state outlives the job, and copies of the callback held by the
  // library must not own Python objects (they may die without the GIL).
  State* state = state_.get();
  return [state](std::string_view stage, double fraction) {
    const std::lock_guard lock(state->mutex);
    if (state->error)
      return;  // already cancelled
    const Clock::time_point now = Clock::now();
    const bool new_stage = stage != state->stage;
    if (!new_stage && std::chrono::duration<double>(now - state->last_poll).count() < kPollSeconds)
      return;
    state->stage = stage;
    state->last_poll = now;
    const py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0)  // a no-op off the main thread
        throw py::error_already_set();
      if (!state->progress.is_none())
        state->progress(py::str(stage.data(), stage.size()), fraction);
    } catch (py::error_already_set& error) {
      state->error.emplace(std::move(error));
    } catch (const std::exception& error) {  // e.g. a result pybind11 could not convert
      PyErr_SetString(PyExc_RuntimeError, error.what());
      state->error.emplace();
    }
    if (state->error)
      request_cancellation(SIGINT);
  };
}

void PythonRun::raise_cancellation() {
  if (state_->error) {
    py::error_already_set error = std::move(*state_->error);
    state_->error.reset();
    throw error;
  }
  // Ctrl-C through the chain: Python's handler raises KeyboardInterrupt now. Elsewhere (a
  // job on another thread stopped by the same Ctrl-C) KeyboardInterrupt is raised here.
  if (PyErr_CheckSignals() != 0)
    throw py::error_already_set();
  PyErr_SetNone(PyExc_KeyboardInterrupt);
  throw py::error_already_set();
}

}  // namespace bemshape::python
