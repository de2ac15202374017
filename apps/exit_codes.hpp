#pragma once
// Exit codes shared by every bemshape subcommand.

namespace bemshape::apps {

/// The run did what was asked.
inline constexpr int kExitSuccess = 0;
/// A requested check ran and failed (e.g. a comparison outside its tolerance).
inline constexpr int kExitCheckFailed = 1;
/// Bad input or usage: unreadable or unusable file, invalid option, resource limit.
inline constexpr int kExitBadInput = 2;
/// Numerical failure: no convergence, singular system, NaN; also internal errors.
inline constexpr int kExitNumericalFailure = 3;
/// --timeout expired: the run produced no result, like a solver that did not converge.
inline constexpr int kExitTimedOut = 3;

/// A signal (SIGINT, SIGTERM) stopped the run: 128 + its number, the shell's convention for
/// a process ended by that signal (130 for SIGINT), so scripts see an interruption, not a
/// numerical failure.
inline constexpr int exit_code_for_signal(int signal) {
  return 128 + signal;
}

}  // namespace bemshape::apps
