#include "analysis/area_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.hpp"

namespace bemshape::analysis {
namespace {

/// Smallest width 1, 2, 2.5 or 5 × 10^m that is at least `w` (> 0). The relative slack keeps
/// an exact round w (0.5) from being pushed to the next width by rounding in the division.
double round_width_up(double w) {
  const double decade = std::pow(10.0, std::floor(std::log10(w)));
  for (const double mantissa : {1.0, 2.0, 2.5, 5.0})
    if (mantissa * decade >= w * (1.0 - 1e-12))
      return mantissa * decade;
  return 10.0 * decade;
}

}  // namespace

AreaHistogram area_histogram(const Eigen::Ref<const Eigen::VectorXd>& values,
                             const Eigen::Ref<const Eigen::VectorXd>& areas, int max_bins,
                             double unmeasurable_from) {
  if (max_bins < 1)
    throw InputError("area histogram: need at least one bin, got " + std::to_string(max_bins));
  if (values.size() != areas.size())
    throw InternalError("area_histogram: " + std::to_string(values.size()) + " values for " +
                        std::to_string(areas.size()) + " areas");
  AreaHistogram h;
  const auto measured = [&](Eigen::Index f) {
    return std::isfinite(values(f)) && values(f) < unmeasurable_from;
  };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (Eigen::Index f = 0; f < values.size(); ++f) {
    if (measured(f)) {
      lo = std::min(lo, values(f));
      hi = std::max(hi, values(f));
    } else {
      h.other_area += areas(f);
    }
  }
  if (!(lo <= hi))
    return h;
  // Equal values: any width works; take one from their magnitude (1 for zeros).
  double width = hi > lo ? round_width_up((hi - lo) / max_bins)
                         : round_width_up(lo != 0.0 ? std::abs(lo) / 10.0 : 1.0);
  double start = std::floor(lo / width) * width;
  // Starting at a multiple of w below lo can need one bin more than (hi − lo)/w: widen until
  // [start, start + bins·w) holds hi, with hi in the last bin.
  int bins = 0;
  for (;;) {
    start = std::floor(lo / width) * width;
    bins = static_cast<int>(std::floor((hi - start) / width)) + 1;
    if (bins <= max_bins)
      break;
    width = round_width_up(width * (1.0 + 1e-9));
  }
  for (int k = 0; k <= bins; ++k)
    h.edges.push_back(start + k * width);
  h.area.assign(static_cast<std::size_t>(bins), 0.0);
  for (Eigen::Index f = 0; f < values.size(); ++f) {
    if (!measured(f))
      continue;
    const int k = std::clamp(static_cast<int>(std::floor((values(f) - start) / width)), 0, bins - 1);
    h.area[static_cast<std::size_t>(k)] += areas(f);
  }
  return h;
}

}  // namespace bemshape::analysis
