#pragma once
// A histogram of non-negative values with "round" bin widths, and its text picture for the
// reports on stdout:
//
//      0% - 0.5%  ########################################  3120
//    0.5% -   1%  ################                          1274
//
// Bins are [k·w, (k + 1)·w), k = 0 … n − 1, with w the smallest of 1, 2, 2.5, 5 × 10^m that
// covers [0, max] in at most `max_bins` bins; the maximum itself goes into the last bin.

#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::apps {

struct Histogram {
  std::vector<double> edges;      ///< n + 1 bin edges, edges[0] = 0 [units of the values]
  std::vector<long long> counts;  ///< n counts
};

/// The histogram of `values` (all ≥ 0 and finite; empty gives no bins). Throws InputError
/// for max_bins < 1.
Histogram histogram(const Eigen::Ref<const Eigen::VectorXd>& values, int max_bins);

/// One line per bin: the edges multiplied by `scale` and followed by `unit` (e.g. 100 and
/// "%" for fractions), a bar of '#' proportional to the count (the fullest bin has
/// `bar_width` characters) and the count. Every line starts with `indent`.
std::string format_histogram(const Histogram& histogram, double scale, const std::string& unit,
                             int bar_width, const std::string& indent);

}  // namespace bemshape::apps
