#include "analysis/histogram.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"

namespace bemshape::analysis {
namespace {

/// Smallest width 1, 2, 2.5 or 5 × 10^m that is at least `w` (> 0).
double round_width_up(double w) {
  const double decade = std::pow(10.0, std::floor(std::log10(w)));
  for (const double mantissa : {1.0, 2.0, 2.5, 5.0, 10.0})
    // Relative slack so that w = 0.5 exactly is not pushed to the next width by rounding in
    // the division by the decade.
    if (mantissa * decade >= w * (1.0 - 1e-12))
      return mantissa * decade;
  return 10.0 * decade;
}

}  // namespace

Histogram histogram(const Eigen::Ref<const Eigen::VectorXd>& values, int max_bins) {
  if (max_bins < 1)
    throw InputError("histogram: need at least one bin, got " + std::to_string(max_bins));
  Histogram h;
  if (values.size() == 0)
    return h;
  const double top = values.maxCoeff();
  // All values 0: one bin [0, 1) of whatever unit, so the picture still shows the count.
  const double width = top > 0.0 ? round_width_up(top / max_bins) : 1.0;
  const int bins = std::clamp(static_cast<int>(std::floor(top / width)) + 1, 1, max_bins);
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  for (int k = 0; k <= bins; ++k)
    h.edges.push_back(k * width);
  for (const double v : values) {
    const int k = std::clamp(static_cast<int>(std::floor(v / width)), 0, bins - 1);
    ++h.counts[static_cast<std::size_t>(k)];
  }
  return h;
}

}  // namespace bemshape::analysis
