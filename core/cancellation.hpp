#pragma once
// Cooperative cancellation of a run: a deadline (the --timeout option), a flag that a
// signal handler may set (SIGINT, SIGTERM) and a flag that the memory watch sets when the
// run outgrows its memory (core/memory_watch.hpp; throw_if_cancelled() then throws
// ResourceError). Long loops below apps/ poll
// cancellation_requested() (cheap: one atomic load, plus one clock read when a deadline is
// set) and stop; code outside OpenMP parallel regions calls throw_if_cancelled(), which
// throws CancelledError. Inside a parallel region an exception cannot leave the region, so
// the loop body skips the remaining iterations once the flag is seen and the thread that
// owns the region calls throw_if_cancelled() right after it.
//
// The state is process-wide because a signal is: one run per process, as in the bemshape
// executable. Tests that set a deadline reset it with clear_cancellation().
//
// Poll points (where a run stops, at the latest after one more unit of work):
//   geometry::prepare_mesh_file  between reading, welding, validation, self-intersection test
//                                and orientation;
//   geometry::refine_to_edge_length  before and after remeshing;
//   bem::solve_transmission_dense    every row of the dense assembly, between LU panels;
//   bem::evaluate_potential          every target point;
//   fem::conjugate_gradient          every iteration;
//   output::AtomicFileWriter         before the rename, so a cancelled run publishes no file.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

#include "core/errors.hpp"

namespace bemshape {

namespace detail {
/// The signal that asked the run to stop, 0 if none. Written by a signal handler, hence a
/// lock-free atomic (async-signal-safe).
inline std::atomic<int> cancellation_signal{0};
/// Deadline as steady_clock ticks since its epoch; 0 = no deadline.
inline std::atomic<std::int64_t> deadline_ticks{0};
/// The timeout the deadline came from [s], for the message.
inline std::atomic<double> timeout_seconds{0.0};
/// Set once by the memory watch (core/memory_watch.hpp) when the run outgrew its memory;
/// the message (what, how much, what to do) is set before the flag, under the mutex.
inline std::atomic<bool> memory_overrun{false};
inline std::mutex& memory_overrun_mutex() {
  static std::mutex m;
  return m;
}
inline std::string& memory_overrun_message() {
  static std::string message;
  return message;
}
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<std::int64_t>::is_always_lock_free,
              "the cancellation flag must be usable from a signal handler");
}  // namespace detail

/// Asks the run to stop because of `signal` (e.g. SIGINT). Async-signal-safe.
inline void request_cancellation(int signal) noexcept {
  detail::cancellation_signal.store(signal, std::memory_order_relaxed);
}

/// Stops the run `seconds` (> 0, wall clock) from now.
inline void set_deadline(double seconds) {
  using Clock = std::chrono::steady_clock;
  const auto ticks = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  detail::timeout_seconds.store(seconds);
  detail::deadline_ticks.store((Clock::now() + ticks).time_since_epoch().count());
}

/// Removes the deadline and any pending request (tests; a new run in the same process).
inline void clear_cancellation() noexcept {
  detail::cancellation_signal.store(0);
  detail::deadline_ticks.store(0);
  detail::memory_overrun.store(false);
}

/// True once a signal asked the run to stop, the deadline has passed or the memory watch
/// saw the run outgrow its memory. Thread-safe.
inline bool cancellation_requested() noexcept {
  if (detail::cancellation_signal.load(std::memory_order_relaxed) != 0) return true;
  if (detail::memory_overrun.load(std::memory_order_relaxed)) return true;
  const std::int64_t deadline = detail::deadline_ticks.load(std::memory_order_relaxed);
  return deadline != 0 && std::chrono::steady_clock::now().time_since_epoch().count() >= deadline;
}

/// Throws CancelledError if cancellation_requested() for a signal or the deadline,
/// ResourceError for the memory watch. Not inside OpenMP parallel regions.
inline void throw_if_cancelled() {
  if (!cancellation_requested()) return;
  const int signal = detail::cancellation_signal.load();
  if (signal == 0 && detail::memory_overrun.load()) {
    std::lock_guard<std::mutex> lock(detail::memory_overrun_mutex());
    throw ResourceError(detail::memory_overrun_message());
  }
  if (signal != 0)
    throw CancelledError("interrupted by signal " + std::to_string(signal) +
                         "; stopped cleanly, no output file was written or changed",
                         signal);
  const double timeout = detail::timeout_seconds.load();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", timeout);
  throw CancelledError(std::string("time limit of ") + seconds +
                           " s (--timeout) reached; stopped cleanly, no output file was written "
                           "or changed; raise --timeout or use a coarser mesh",
                       0);
}

}  // namespace bemshape
