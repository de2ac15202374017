// The treecode's near-field rule table (bem/evaluate/near_panel_integrals.hpp) against the
// adaptive reference: values and gradients of the Laplace single and double layer within
// the table's accuracy at every distance ratio of every row, and the calibration loop that
// prints the errors behind the table.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "bem/evaluate/near_panel_integrals.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"
#include "tests/bem/panel_reference.hpp"

using namespace bemshape;
using Eigen::Vector3d;

namespace {

using testing::rule_test_panels;
using testing::target_directions;

/// The error of `v` against the reference, relative to the entry's natural magnitude at
/// distance r (area·|G^{(k)}(r)| for the k-th derivative), the worst of the four.
double scaled_error(const bem::PanelIntegrals& v, const testing::ReferenceIntegrals& ref,
                    const bem::Panel& p, double r) {
  const double g0 = 1.0 / (4 * M_PI * r), g1 = g0 / r, g2 = 2.0 * g1 / r;
  return std::max({std::abs(v.single_layer - ref.single_layer) / (p.area * g0),
                   std::abs(v.double_layer - ref.double_layer) / (p.area * g1),
                   (v.single_layer_gradient - ref.single_layer_gradient).norm() / (p.area * g1),
                   (v.double_layer_gradient - ref.double_layer_gradient).norm() / (p.area * g2)});
}

}  // namespace

TEST_CASE("near panel integrals: measured errors of candidate rules (prints the table)",
          "[.calibration][near_panel_integrals]") {
  struct Named {
    const char* name;
    const bem::TriangleRule* rule;
  };
  const std::vector<Named> rules = {
      {"sym2", &bem::symmetric_triangle_rule(2)}, {"sym4", &bem::symmetric_triangle_rule(4)},
      {"sym5", &bem::symmetric_triangle_rule(5)}, {"sym6", &bem::symmetric_triangle_rule(6)},
      {"sym8", &bem::symmetric_triangle_rule(8)}, {"col4", &bem::collapsed_gauss_rule(4)},
      {"col5", &bem::collapsed_gauss_rule(5)},    {"col6", &bem::collapsed_gauss_rule(6)},
      {"col7", &bem::collapsed_gauss_rule(7)},    {"col8", &bem::collapsed_gauss_rule(8)},
      {"col10", &bem::collapsed_gauss_rule(10)}};
  for (double ratio : {0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 6.0, 8.0, 12.0, 20.0, 40.0}) {
    std::vector<double> worst(rules.size(), 0.0);
    for (const bem::Panel& p : rule_test_panels())
      for (const Vector3d& dir : target_directions(43, 1)) {
        const Vector3d x = p.centroid + ratio * p.diameter * dir;
        const auto ref = testing::reference_panel_integrals(0.0, p, x, true, 1e-12);
        for (size_t i = 0; i < rules.size(); ++i)
          worst[i] = std::max(worst[i], scaled_error(bem::gauss_panel_integrals(
                                                         bem::LaplaceKernel{}, p, x, *rules[i].rule, true),
                                                     ref, p, ratio * p.diameter));
      }
    std::cout << "ratio " << ratio << ":";
    for (size_t i = 0; i < rules.size(); ++i) std::cout << " " << rules[i].name << " " << worst[i];
    std::cout << "\n";
  }
}

TEST_CASE("near panel integrals: within their accuracy at every distance, exact below the table",
          "[near_panel_integrals]") {
  // Other directions than the calibration's, ratios at and between the rows' thresholds.
  double worst = 0.0;
  for (const bem::Panel& p : rule_test_panels())
    for (double ratio : {0.3, 0.7, 1.0, 1.2, 1.5, 1.7, 2.0, 2.2, 2.5, 3.0, 4.0, 5.0, 10.0, 40.0, 100.0})
      for (const Vector3d& dir : target_directions(6, 5)) {
        const Vector3d x = p.centroid + ratio * p.diameter * dir;
        const auto ref = testing::reference_panel_integrals(0.0, p, x, true, 1e-10);
        const double e = scaled_error(bem::near_panel_integrals(p, x, true), ref, p,
                                      ratio * p.diameter);
        INFO("ratio " << ratio << ", direction " << dir.transpose());
        CHECK(e < bem::kNearPanelAccuracy);
        worst = std::max(worst, e);
      }
  WARN("near_panel_integrals: worst scaled error " << worst);
}

TEST_CASE("near panel integrals: the values alone are the values of the gradient path",
          "[near_panel_integrals]") {
  const bem::Panel p = rule_test_panels()[2];
  for (double ratio : {1.1, 1.8, 3.0, 6.0, 50.0}) {
    const Vector3d x = p.centroid + ratio * p.diameter * Vector3d(0.3, -0.5, 0.8).normalized();
    const bem::PanelIntegrals with = bem::near_panel_integrals(p, x, true);
    const bem::PanelIntegrals without = bem::near_panel_integrals(p, x, false);
    CHECK(without.single_layer == Approx(with.single_layer).epsilon(1e-12));
    CHECK(without.double_layer == Approx(with.double_layer).epsilon(1e-12));
  }
}
