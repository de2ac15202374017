#pragma once
// Progress of a long bemshape run on stderr, fed by the ProgressCallback every library stage
// takes (core/progress.hpp):
//
//   terminal:      one line rewritten in place, "  assemble   42%   12.3 s", at most every
//                  kRedrawSeconds, finished with a newline when the stage changes;
//   not terminal:  one line per stage when it ends, "  assemble  done  12.3 s  (total 15.0 s)",
//                  so logs of batch runs stay short;
//   quiet:         nothing;
//   silent_seconds: nothing either until the run has taken that long, so commands that are
//                  usually quick (`check`) show progress on large inputs only.
//
// Safe to call from several threads (a mutex guards the output).

#include <chrono>
#include <exception>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "core/progress.hpp"

namespace bemshape::apps {

class ProgressDisplay {
 public:
  enum class Mode { quiet, lines, live };

  /// quiet → Mode::quiet; otherwise live if stderr is a terminal, else lines. Nothing is
  /// shown before `silent_seconds` [s] have passed since construction.
  explicit ProgressDisplay(bool quiet, double silent_seconds = 0.0);
  /// Writes to `out` in the given mode (tests).
  ProgressDisplay(Mode mode, std::ostream& out, double silent_seconds = 0.0);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  /// A callback forwarding to update(); valid while this object lives.
  ProgressCallback callback();
  /// Reports `fraction` ∈ [0, 1] of `stage` done; a new stage name ends the previous stage.
  void update(std::string_view stage, double fraction);
  /// Ends the current stage (prints its final line). The destructor does the same, with
  /// "stopped" instead of "done" when an exception is unwinding the run.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  /// Prints the current stage's final line with `status` ("done", "stopped").
  void end_stage_locked(const char* status);

  Mode mode_;
  std::ostream& out_;
  double silent_seconds_ = 0.0;
  std::mutex mutex_;
  std::string stage_;
  double fraction_ = 0.0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point stage_start_ = start_;
  Clock::time_point last_draw_{};
  /// std::uncaught_exceptions() at construction: more at destruction means unwinding.
  int uncaught_exceptions_ = std::uncaught_exceptions();
};

}  // namespace bemshape::apps
