// core/cancellation.hpp: a deadline and a signal request both stop a run, with messages that
// say why, and clearing them lets the next run go on.
#include <catch2/catch.hpp>

#include <csignal>
#include <thread>

#include "core/cancellation.hpp"

using namespace bemshape;

TEST_CASE("no deadline and no signal: nothing is cancelled") {
  clear_cancellation();
  CHECK_FALSE(cancellation_requested());
  CHECK_NOTHROW(throw_if_cancelled());
}

TEST_CASE("a deadline cancels once it has passed, with a message naming --timeout") {
  clear_cancellation();
  set_deadline(0.05);
  CHECK_FALSE(cancellation_requested());
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  CHECK(cancellation_requested());
  try {
    throw_if_cancelled();
    FAIL("no exception");
  } catch (const CancelledError& e) {
    CHECK(e.signal() == 0);
    CHECK_THAT(e.what(), Catch::Contains("--timeout") && Catch::Contains("0.05 s"));
  }
  clear_cancellation();
  CHECK_FALSE(cancellation_requested());
}

TEST_CASE("a signal's request cancels at once and the error carries the signal number") {
  clear_cancellation();
  request_cancellation(SIGINT);
  CHECK(cancellation_requested());
  try {
    throw_if_cancelled();
    FAIL("no exception");
  } catch (const CancelledError& e) {
    CHECK(e.signal() == SIGINT);
    CHECK_THAT(e.what(), Catch::Contains("interrupted by signal"));
  }
  clear_cancellation();
}
