#pragma once
// Wall-time bounds for the tests whose requirement is that something happens "in seconds":
// a refusal before any solve, a command that does no BEM work. Such a bound separates "did
// not solve" (a fraction of the bound) from "solved" (many times it); it is not a speed target
// (those are measured by bench/, never asserted).
//
// Each bound is written for the Release build. The sanitizer build checks every memory access
// and runs the same work 5–15 times slower (docs/reliability.md, "Sanitizers"), so there the
// bounds are multiplied by BEMSHAPE_TEST_TIME_SCALE, which tests/CMakeLists.txt sets.

#ifndef BEMSHAPE_TEST_TIME_SCALE
#define BEMSHAPE_TEST_TIME_SCALE 1.0
#endif

namespace bemshape::test {

/// The bound [s] for work that takes well under `release_seconds` in a Release build.
constexpr double time_bound(double release_seconds) {
  return release_seconds * BEMSHAPE_TEST_TIME_SCALE;
}

}  // namespace bemshape::test
