#pragma once
// The ways a bemshape run can fail, each with its own exit code in apps/:
//   InputError      — the user's input or options are unusable (exit code 2);
//   ResourceError   — the run would exceed a memory or size limit (exit code 2; the message
//                     names the option or path to use instead);
//   NumericalError  — a solver did not converge, a factorisation was singular, or a NaN
//                     appeared (exit code 3);
//   CancelledError  — --timeout expired (exit code 3) or a signal stopped the run (exit code
//                     128 + signal, 130 for SIGINT); see core/cancellation.hpp.
// Messages say what is wrong, where (file, count, coordinates) and what the user can do.

#include <stdexcept>
#include <string>

namespace bemshape {

/// Bad user input: unreadable or invalid file, unusable mesh, contradictory options.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A request that would exceed a memory, size or time budget.
class ResourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Numerical failure: no convergence, singular system, NaN/Inf in a result.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The run was stopped before it finished: the --timeout deadline passed (signal() == 0) or
/// a signal such as SIGINT asked it to stop (signal() is its number).
class CancelledError : public std::runtime_error {
 public:
  CancelledError(const std::string& what, int signal) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_ = 0;
};

/// A broken internal invariant (a bug in bemshape, never the user's fault).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace bemshape
