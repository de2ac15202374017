#pragma once
// Memory limits for the tests that make the guard refuse or stop a run (apps/run_limits.hpp):
// a limit between what the process holds before a stage and what that stage would reach.
//
// Each limit is written for the Release build. The sanitizer build holds about 0.15 GB more
// from its start (AddressSanitizer's shadow memory and allocator), and up to 0.2 GB once a
// part is read and remeshed (freed blocks wait in ASan's quarantine), so a limit chosen just
// above Release's holding would stop the run at an earlier stage than the test is about
// (docs/reliability.md, "Sanitizers"). There the limits are raised by
// BEMSHAPE_TEST_RESIDENT_OVERHEAD_MB, which tests/CMakeLists.txt sets.

#ifndef BEMSHAPE_TEST_RESIDENT_OVERHEAD_MB
#define BEMSHAPE_TEST_RESIDENT_OVERHEAD_MB 0
#endif

namespace bemshape::test {

/// The limit [MB, 10⁶ bytes] standing for `release_megabytes` of a Release build.
constexpr unsigned long long resident_bound_mb(unsigned long long release_megabytes) {
  return release_megabytes + BEMSHAPE_TEST_RESIDENT_OVERHEAD_MB;
}

}  // namespace bemshape::test
