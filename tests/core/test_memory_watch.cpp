// core/memory_watch.hpp: the running account stops a run that outgrows its limit at the
// next poll point with a ResourceError naming the size, and a failed allocation in a
// parallel loop becomes the same error after the loop.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <memory>
#include <thread>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/memory_watch.hpp"

using namespace bemshape;

namespace {

/// Polls cancellation_requested() for up to `seconds`, as a long loop does.
bool stopped_within(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (cancellation_requested()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

std::string thrown_message() {
  try {
    throw_if_cancelled();
  } catch (const ResourceError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("memory watch: the process's sizes are read from /proc") {
  const ProcessMemory m = process_memory();
  CHECK(m.resident > 0);
  CHECK(m.virtual_size >= m.resident);
  // A limit of 1 GB more than the process holds is the limit (the machine has more).
  const std::uint64_t limit = m.resident + 1'000'000'000;
  std::string reason;
  if (available_memory_bytes() > 2'000'000'000) {
    CHECK(resident_memory_limit_bytes(limit, &reason) == limit);
    CHECK(reason == " (--max-memory)");
  }
}

TEST_CASE("memory watch: growing past --max-memory stops the run at the next poll point") {
  clear_cancellation();
  {
    // The limit 64 MB above what the process holds now; then 256 MB are written.
    const std::uint64_t limit = process_memory().resident + 64'000'000;
    const MemoryWatch watch(limit);
    set_memory_context("the test's array", "use a smaller array");
    CHECK_FALSE(stopped_within(0.2));
    const std::size_t bytes = 256'000'000;
    const std::unique_ptr<char[]> block(new char[bytes]);
    std::memset(block.get(), 1, bytes);  // resident only once written
    CHECK(stopped_within(2.0));
    const std::string message = thrown_message();
    CAPTURE(message);
    CHECK_THAT(message, Catch::StartsWith("the test's array: the process holds ") &&
                            Catch::Contains(" GB it may use (--max-memory); stopped cleanly") &&
                            Catch::EndsWith("use a smaller array"));
    CHECK(watched_peak_resident_bytes() > limit);
    CHECK(block[bytes - 1] == 1);
  }
  clear_cancellation();
  CHECK_FALSE(cancellation_requested());
}

TEST_CASE("memory watch: a failed allocation in a parallel loop becomes a ResourceError") {
  clear_cancellation();
  set_memory_context("the test's loop", "use less memory");
  note_failed_allocation();
  note_failed_allocation();  // the first one is kept
  CHECK(cancellation_requested());
  CHECK_THAT(thrown_message(), Catch::StartsWith("the test's loop: an allocation failed with the "
                                                 "process holding ") &&
                                   Catch::EndsWith("; use less memory"));
  clear_cancellation();
}
