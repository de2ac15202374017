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

}  // namespace bemshape::apps
