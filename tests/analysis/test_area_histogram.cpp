// analysis/area_histogram.hpp: bins of round width, every face's area in the bin of its value,
// unmeasurable faces counted apart; the areas add up to the surface's.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "analysis/area_histogram.hpp"
#include "core/errors.hpp"

using namespace bemshape;

TEST_CASE("area histogram: round bins from a multiple of the width, areas by hand") {
  Eigen::VectorXd values(5), areas(5);
  values << 0.3, 1.7, 2.2, 9.9, 2e6;
  areas << 1, 2, 3, 4, 8;
  // (9.9 − 0.3)/5 = 1.92 → width 2 from 0: [0,2) 1+2, [2,4) 3, [8,10) 4; 2e6 unmeasurable.
  const analysis::AreaHistogram h = analysis::area_histogram(values, areas, 5, 1e6);
  CHECK(h.edges == std::vector<double>{0, 2, 4, 6, 8, 10});
  CHECK(h.area == std::vector<double>{3, 3, 0, 0, 4});
  CHECK(h.other_area == 8);
}

TEST_CASE("area histogram: the areas add up, each bin holds its values, at most max_bins") {
  const int n = 1000;
  Eigen::VectorXd values(n), areas(n);
  for (int i = 0; i < n; ++i) {
    values(i) = 3.7 + 11.3 * std::pow(std::sin(0.37 * i), 2);
    areas(i) = 0.5 + (i % 7);
  }
  values(17) = std::numeric_limits<double>::quiet_NaN();
  for (const int bins : {1, 3, 12, 40}) {
    const analysis::AreaHistogram h = analysis::area_histogram(values, areas, bins, 1e6);
    REQUIRE(h.area.size() + 1 == h.edges.size());
    CHECK(int(h.area.size()) <= bins);
    const double width = h.edges[1] - h.edges[0];
    const double mantissa = width / std::pow(10.0, std::floor(std::log10(width)));
    CHECK((std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
           std::abs(mantissa - 2.5) < 1e-9 || std::abs(mantissa - 5) < 1e-9));
    double total = 0.0;
    for (const double a : h.area)
      total += a;
    CHECK(total + h.other_area == Approx(areas.sum()).epsilon(1e-12));
    CHECK(h.other_area == areas(17));
    CHECK(h.edges.front() <= 3.7);
    CHECK(h.edges.back() > values.maxCoeff());
  }
}

TEST_CASE("area histogram: equal values, nothing measurable, bad bin count") {
  const Eigen::VectorXd areas = Eigen::VectorXd::Constant(3, 2.0);
  const analysis::AreaHistogram equal =
      analysis::area_histogram(Eigen::VectorXd::Constant(3, 4.0), areas, 12, 1e6);
  REQUIRE(equal.area.size() == 1);
  CHECK(equal.area[0] == 6.0);
  CHECK(equal.edges[0] <= 4.0);
  CHECK(equal.edges[1] > 4.0);
  const analysis::AreaHistogram none =
      analysis::area_histogram(Eigen::VectorXd::Constant(3, 5e6), areas, 12, 1e6);
  CHECK(none.area.empty());
  CHECK(none.other_area == 6.0);
  CHECK_THROWS_AS(analysis::area_histogram(areas, areas, 0, 1e6), InputError);
  CHECK_THROWS_AS(analysis::area_histogram(areas, Eigen::VectorXd(2), 3, 1e6), InternalError);
}
