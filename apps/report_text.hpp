#pragma once
// Number formatting of the human-readable reports on stdout (JSON and the data files use
// full precision elsewhere: apps/output/number_text.hpp).

#include <cstdio>
#include <string>

#include <Eigen/Core>

namespace bemshape::apps {

/// x with `digits` significant digits (printf %g): "12.7", "0.000123", "1.5e+06".
inline std::string number_text(double x, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

/// "(x, y, z)" with six significant digits per coordinate [model units].
inline std::string point_text(const Eigen::Vector3d& p) {
  return "(" + number_text(p.x(), 6) + ", " + number_text(p.y(), 6) + ", " + number_text(p.z(), 6) +
         ")";
}

}  // namespace bemshape::apps
