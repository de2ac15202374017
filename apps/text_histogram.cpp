#include "apps/text_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "apps/report_text.hpp"

namespace bemshape::apps {

std::string format_histogram(const analysis::Histogram& histogram, double scale,
                             const std::string& unit, int bar_width, const std::string& indent) {
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

std::string format_area_histogram(const analysis::AreaHistogram& histogram, int bar_width,
                                  const std::string& indent) {
  std::vector<std::string> lower, upper;
  std::size_t lower_width = 0, upper_width = 0;
  for (std::size_t k = 0; k + 1 < histogram.edges.size(); ++k) {
    lower.push_back(number_text(histogram.edges[k], 4));
    upper.push_back(number_text(histogram.edges[k + 1], 4));
    lower_width = std::max(lower_width, lower.back().size());
    upper_width = std::max(upper_width, upper.back().size());
  }
  double fullest = 0.0, total = 0.0;
  for (const double a : histogram.area) {
    fullest = std::max(fullest, a);
    total += a;
  }
  std::ostringstream out;
  for (std::size_t k = 0; k < histogram.area.size(); ++k) {
    const double a = histogram.area[k];
    const auto length = static_cast<std::size_t>(
        a <= 0.0 ? 0 : std::max<long long>(1, std::llround(a * bar_width / fullest)));
    char share[16];
    std::snprintf(share, sizeof share, "%5.1f %%", total > 0.0 ? 100.0 * a / total : 0.0);
    out << indent << std::string(lower_width - lower[k].size(), ' ') << lower[k] << " - "
        << std::string(upper_width - upper[k].size(), ' ') << upper[k] << "  "
        << std::string(length, '#')
        << std::string(static_cast<std::size_t>(bar_width) - length, ' ') << "  " << share
        << '\n';
  }
  return out.str();
}

}  // namespace bemshape::apps
