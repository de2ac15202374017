// analysis/histogram.hpp: bin widths of 1, 2, 2.5 or 5 × 10^m, the maximum in the last bin.
#include <catch2/catch.hpp>

#include "analysis/histogram.hpp"
#include "core/errors.hpp"

using namespace bemshape;

TEST_CASE("histogram: round bin width covering the maximum, counts per bin") {
  const Eigen::VectorXd values = (Eigen::VectorXd(4) << 0.1, 0.3, 0.35, 1.0).finished();
  // 1.0 / 4 bins = 0.25, already round: edges 0, 0.25, 0.5, 0.75, 1; 1.0 joins the last bin.
  const analysis::Histogram h = analysis::histogram(values, 4);
  REQUIRE(h.edges.size() == 5);
  CHECK(h.edges[1] == Approx(0.25));
  CHECK(h.edges[4] == Approx(1.0));
  CHECK(h.counts == std::vector<long long>{1, 2, 0, 1});
  // 1.0 / 3 bins = 0.33 rounds up to 0.5: 1.0 starts the third bin [1, 1.5).
  const analysis::Histogram coarse = analysis::histogram(values, 3);
  REQUIRE(coarse.edges.size() == 4);
  CHECK(coarse.edges[1] == Approx(0.5));
  CHECK(coarse.edges[3] == Approx(1.5));
  CHECK(coarse.counts == std::vector<long long>{3, 0, 1});
  CHECK(analysis::histogram(Eigen::VectorXd(), 4).counts.empty());
  CHECK_THROWS_AS(analysis::histogram(values, 0), InputError);
}
