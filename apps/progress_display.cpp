#include "apps/progress_display.hpp"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <iostream>

namespace bemshape::apps {
namespace {

/// Redraw interval of the live line: ten updates a second look continuous and cost nothing.
constexpr double kRedrawSeconds = 0.1;

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

std::string format_line(const std::string& stage, const char* status, double stage_seconds,
                        double total_seconds) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "  %-20s %5s %8.1f s  (total %.1f s)", stage.c_str(), status,
                stage_seconds, total_seconds);
  return buffer;
}

}  // namespace

ProgressDisplay::ProgressDisplay(bool quiet, double silent_seconds)
    : ProgressDisplay(quiet                     ? Mode::quiet
                      : ::isatty(STDERR_FILENO) ? Mode::live
                                                : Mode::lines,
                      std::cerr, silent_seconds) {}

ProgressDisplay::ProgressDisplay(Mode mode, std::ostream& out, double silent_seconds)
    : mode_(mode), out_(out), silent_seconds_(silent_seconds) {}

ProgressDisplay::~ProgressDisplay() {
  // Unwinding from an error or a cancellation: the current stage did not finish.
  if (mode_ == Mode::quiet)
    return;
  const std::lock_guard lock(mutex_);
  end_stage_locked(std::uncaught_exceptions() > uncaught_exceptions_ ? "stopped" : "done");
}

ProgressCallback ProgressDisplay::callback() {
  if (mode_ == Mode::quiet)
    return {};
  return [this](std::string_view stage, double fraction) { update(stage, fraction); };
}

void ProgressDisplay::update(std::string_view stage, double fraction) {
  if (mode_ == Mode::quiet)
    return;
  const std::lock_guard lock(mutex_);
  const auto now = Clock::now();
  if (stage != stage_) {
    end_stage_locked("done");
    stage_ = stage;
    stage_start_ = now;
    last_draw_ = {};
  }
  fraction_ = fraction;
  if (mode_ == Mode::live && seconds(now - last_draw_) >= kRedrawSeconds &&
      seconds(now - start_) >= silent_seconds_) {
    char percent[16];
    std::snprintf(percent, sizeof percent, "%3.0f%%", 100.0 * fraction);
    out_ << '\r' << format_line(stage_, percent, seconds(now - stage_start_), seconds(now - start_))
         << std::flush;
    last_draw_ = now;
  }
}

void ProgressDisplay::finish() {
  if (mode_ == Mode::quiet)
    return;
  const std::lock_guard lock(mutex_);
  end_stage_locked("done");
}

void ProgressDisplay::end_stage_locked(const char* status) {
  if (stage_.empty())
    return;
  const auto now = Clock::now();
  if (seconds(now - start_) < silent_seconds_) {
    stage_.clear();
    return;
  }
  const std::string line =
      format_line(stage_, status, seconds(now - stage_start_), seconds(now - start_));
  if (mode_ == Mode::live)
    out_ << '\r' << line << "\x1b[K\n" << std::flush;
  else
    out_ << line << '\n' << std::flush;
  stage_.clear();
}

}  // namespace bemshape::apps
