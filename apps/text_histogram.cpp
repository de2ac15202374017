#include "apps/text_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "apps/report_text.hpp"
#include "core/errors.hpp"

namespace bemshape::apps {
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

std::string format_histogram(const Histogram& histogram, double scale, const std::string& unit,
                             int bar_width, const std::string& indent) {
  std::vector<std::string> lower, upper;
  std::size_t lower_width = 0, upper_width = 0;
  for (std::size_t k = 0; k + 1 < histogram.edges.size(); ++k) {
    lower.push_back(number_text(scale * histogram.edges[k], 4) + unit);
    upper.push_back(number_text(scale * histogram.edges[k + 1], 4) + unit);
    lower_width = std::max(lower_width, lower.back().size());
    upper_width = std::max(upper_width, upper.back().size());
  }
  long long fullest = 1;
  for (const long long c : histogram.counts)
    fullest = std::max(fullest, c);
  std::ostringstream out;
  for (std::size_t k = 0; k < histogram.counts.size(); ++k) {
    const long long c = histogram.counts[k];
    // A non-empty bin shows at least one '#', so no count disappears from the picture.
    const auto length = static_cast<std::size_t>(
        c == 0 ? 0 : std::max<long long>(1, std::llround(double(c) * bar_width / double(fullest))));
    out << indent << std::string(lower_width - lower[k].size(), ' ') << lower[k] << " - "
        << std::string(upper_width - upper[k].size(), ' ') << upper[k] << "  "
        << std::string(length, '#')
        << std::string(static_cast<std::size_t>(bar_width) - length, ' ') << "  " << c << '\n';
  }
  return out.str();
}

}  // namespace bemshape::apps
