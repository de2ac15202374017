#pragma once
// A histogram of non-negative values with "round" bin widths: bins [k·w, (k + 1)·w),
// k = 0 … n − 1, with w the smallest of 1, 2, 2.5, 5 × 10^m that covers [0, max] in at most
// `max_bins` bins; the maximum itself goes into the last bin. (apps/text_histogram.hpp
// draws it for the reports on stdout.)

#include <vector>

#include <Eigen/Core>

namespace bemshape::analysis {

struct Histogram {
  std::vector<double> edges;      ///< n + 1 bin edges, edges[0] = 0 [units of the values]
  std::vector<long long> counts;  ///< n counts
};

/// The histogram of `values` (all ≥ 0 and finite; empty gives no bins). Throws InputError
/// for max_bins < 1.
Histogram histogram(const Eigen::Ref<const Eigen::VectorXd>& values, int max_bins);

}  // namespace bemshape::analysis
