#pragma once
// Number formatting of the human-readable reports on stdout (JSON and the data files use
// full precision elsewhere: apps/output/number_text.hpp): number_text (core/number_text.hpp)
// and points.

#include <string>

#include <Eigen/Core>

#include "core/number_text.hpp"

namespace bemshape::apps {

/// "(x, y, z)" with six significant digits per coordinate [model units].
inline std::string point_text(const Eigen::Vector3d& p) {
  return "(" + number_text(p.x(), 6) + ", " + number_text(p.y(), 6) + ", " + number_text(p.z(), 6) +
         ")";
}

}  // namespace bemshape::apps
