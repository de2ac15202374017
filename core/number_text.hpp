#pragma once
// Numbers in messages and in the human-readable reports, to a given number of significant
// digits (the data files and JSON reports keep full precision: apps/output/number_text.hpp).

#include <cstdio>
#include <string>

namespace bemshape {

/// x with `digits` significant digits (printf %g): "12.7", "0.000123", "1.5e+06".
inline std::string number_text(double x, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

}  // namespace bemshape
