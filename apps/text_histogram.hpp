#pragma once
// The text picture of a histogram (analysis/histogram.hpp) for the reports on stdout:
//
//      0% - 0.5%  ########################################  3120
//    0.5% -   1%  ################                          1274

#include <string>

#include "analysis/area_histogram.hpp"
#include "analysis/histogram.hpp"

namespace bemshape::apps {

/// One line per bin: the edges multiplied by `scale` and followed by `unit` (e.g. 100 and
/// "%" for fractions), a bar of '#' proportional to the count (the fullest bin has
/// `bar_width` characters) and the count. Every line starts with `indent`.
std::string format_histogram(const analysis::Histogram& histogram, double scale,
                             const std::string& unit, int bar_width, const std::string& indent);

/// The same for an area histogram: one line per bin with its edges, a bar proportional to the
/// bin's area and the bin's share of the measured area in %.
std::string format_area_histogram(const analysis::AreaHistogram& histogram, int bar_width,
                                  const std::string& indent);

}  // namespace bemshape::apps
