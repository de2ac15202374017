// Catch2 runner for every bemshape test suite. In Debug builds it traps invalid
// floating-point operations (the ones that create NaN), so a NaN fails the test at the line
// that made it instead of surfacing as a wrong number later.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cfenv>

int main(int argc, char* argv[]) {
#ifndef NDEBUG
  feenableexcept(FE_INVALID);
#endif
  return Catch::Session().run(argc, argv);
}
