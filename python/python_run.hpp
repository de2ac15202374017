#pragma once
// One library job run from Python: what every function of the module does around the call
// into bemshape::analysis.
//
//   • The GIL is released for the whole job, so other Python threads run meanwhile.
//   • threads=N sets the OpenMP threads of this call only (the previous count is restored).
//   • Ctrl-C (SIGINT) stops the job at its next poll point (core/cancellation.hpp) and
//     raises KeyboardInterrupt, within about a second even in the longest loops:
//       – on the main thread, while Python's SIGINT handler is its default one, a C handler
//         is chained in front of it for the job's duration: it requests the cancellation and
//         passes the signal on, so Python raises KeyboardInterrupt as soon as the job stops;
//       – in every case, the job's progress reports re-acquire the GIL at most every
//         kPollSeconds and run Python's pending signal handlers (PyErr_CheckSignals): an
//         exception from a handler of the user's own (e.g. a timeout on SIGALRM) cancels the
//         job and is raised in its place.
//     The cancellation state is the process's: a Ctrl-C stops every job running in it.
//   • progress=callable(stage: str, fraction: float) is called with the GIL held at most
//     every kPollSeconds and at every new stage; an exception from it cancels the job and is
//     raised in its place.
//   • The library's errors become the module's exceptions (bemshape_module.cpp): InputError
//     → ValueError, ResourceError → MemoryError, NumericalError → RuntimeError.

#include <memory>
#include <optional>
#include <utility>

#include <pybind11/pybind11.h>

#include "core/errors.hpp"
#include "core/progress.hpp"

namespace bemshape::python {

namespace py = pybind11;

/// Interval between two calls into Python from a job's progress reports [s]: short enough
/// for Ctrl-C and custom handlers to feel immediate, long enough to cost nothing (each poll
/// takes the GIL for microseconds).
inline constexpr double kPollSeconds = 0.05;

class PythonRun {
 public:
  /// With the GIL held. `threads`: OpenMP threads for the job (> 0), empty for the current
  /// count; `progress`: a callable or None.
  PythonRun(std::optional<int> threads, py::object progress);
  ~PythonRun();
  PythonRun(const PythonRun&) = delete;
  PythonRun& operator=(const PythonRun&) = delete;

  /// Runs `job(progress_callback)` with the GIL released and returns its result; translates
  /// a cancellation into the Python exception that caused it (KeyboardInterrupt for Ctrl-C).
  template <class Job>
  auto operator()(Job&& job) {
    using Result = decltype(job(ProgressCallback{}));
    std::optional<Result> result;
    try {
      const py::gil_scoped_release release;
      result.emplace(job(callback()));
    } catch (const CancelledError&) {
      raise_cancellation();  // the GIL is held again here
    }
    return std::move(*result);
  }

  /// The OpenMP threads the job runs with.
  int threads() const;

 private:
  struct State;
  ProgressCallback callback();
  /// Throws py::error_already_set: the stored Python error, else KeyboardInterrupt.
  [[noreturn]] void raise_cancellation();

  std::shared_ptr<State> state_;
  int previous_threads_ = 0;
  bool sigint_chained_ = false;
};

}  // namespace bemshape::python
