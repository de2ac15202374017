#pragma once
// Progress reporting without I/O: library code below apps/ never prints. Long-running
// algorithms take a ProgressCallback and call it with the name of the current stage and the
// fraction done in [0, 1]; apps/ turns the calls into a progress line on stderr.

#include <functional>
#include <string_view>

namespace bemshape {

/// Called as progress(stage, fraction) with fraction in [0, 1]. May be empty.
using ProgressCallback = std::function<void(std::string_view stage, double fraction)>;

/// Calls `progress` if it is set.
inline void report_progress(const ProgressCallback& progress, std::string_view stage,
                            double fraction) {
  if (progress) progress(stage, fraction);
}

}  // namespace bemshape
