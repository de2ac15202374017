#pragma once
// BEMSHAPE_ASSERT(condition, message): internal invariants. Active in Debug builds and in the
// test suite (which defines BEMSHAPE_ENABLE_ASSERTS); compiled out of Release binaries so
// that hot loops pay nothing. A failed assertion throws bemshape::InternalError with the
// file and line, so a test reports it instead of aborting the whole run.

#include <string>

#include "core/errors.hpp"

#if !defined(NDEBUG) || defined(BEMSHAPE_ENABLE_ASSERTS)
#define BEMSHAPE_ASSERT(condition, message)                                              \
  do {                                                                                   \
    if (!(condition))                                                                    \
      throw ::bemshape::InternalError(std::string(__FILE__) + ":" +                      \
                                      std::to_string(__LINE__) + ": assertion '" +       \
                                      #condition "' failed: " + std::string(message));   \
  } while (false)
#else
#define BEMSHAPE_ASSERT(condition, message) \
  do {                                      \
  } while (false)
#endif
