#pragma once
// The area of a surface per range of a per-face value (thickness): how much of the part is how
// thick, for the HTML report (and later the text and JSON reports).
//
//   values: #F per-face values [model units]; faces whose value is not finite or at or above
//           `unmeasurable_from` (the features' saturation value kMaxThicknessFactor·h0,
//           features/thickness.hpp) are left out and their area is counted in other_area
//   areas:  #F face areas [model units²]
//
// Bins are [edges[k], edges[k + 1]) of one round width w (1, 2, 2.5 or 5 × 10^m), the
// smallest such width that covers [min, max] of the measured values in at most `max_bins`
// bins, starting at a multiple of w; the maximum itself goes into the last bin. Each face adds
// its whole area to the bin of its value, so the bins' areas sum to the measured area.

#include <vector>

#include <Eigen/Core>

namespace bemshape::analysis {

struct AreaHistogram {
  std::vector<double> edges;  ///< n + 1 increasing edges [model units]
  std::vector<double> area;   ///< n areas [model units²]
  double other_area = 0.0;    ///< area of the faces left out [model units²]
};

/// Throws InputError for max_bins < 1, InternalError if the sizes differ. No measured face
/// gives no bins; all values equal give one bin of width w around them.
AreaHistogram area_histogram(const Eigen::Ref<const Eigen::VectorXd>& values,
                             const Eigen::Ref<const Eigen::VectorXd>& areas, int max_bins,
                             double unmeasurable_from);

}  // namespace bemshape::analysis
