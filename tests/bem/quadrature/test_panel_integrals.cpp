// integrate_panel against the adaptive reference over the whole range of distance ratios
// (which exercises every row of the far-field rule table), against closed forms on closed
// polyhedra, and for invariance under rigid motions.
#include <catch2/catch.hpp>
#include <cmath>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <vector>

#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/bem/panel_reference.hpp"

using namespace bemshape;
using bem::LaplaceKernel;
using bem::YukawaKernel;
using Eigen::Vector3d;

namespace {

constexpr double required_accuracy = 1e-8;
/// See test_polar_quadrature.cpp: entries below 1e−6 of the near-field magnitude are compared
/// in absolute terms.
constexpr double magnitude_floor = 1e-6;

double relative_error(double value, double reference, double magnitude) {
  return std::abs(value - reference) / std::max(std::abs(reference), magnitude_floor * magnitude);
}
double relative_error(const Vector3d& value, const Vector3d& reference, double magnitude) {
  return (value - reference).norm() / std::max(reference.norm(), magnitude_floor * magnitude);
}

using testing::rule_test_panels;
using testing::target_directions;

struct NamedRule {
  const char* name;
  const bem::TriangleRule* rule;
};

/// The calibration loop behind a rule table: for each κ·diameter and distance ratio, the
/// worst of error(reference, rule, panel, x, κ, r) of each rule over three panel shapes and
/// 43 directions, printed as one line per ratio; the adaptive reference (with gradients if
/// `with_gradients`) is computed once per target for all rules. Cells with
/// κ·(r − 0.6·diameter) above `max_kappa_gap` are skipped (their entries are cut off to 0).
template <class Error>
void print_worst_errors(const std::vector<NamedRule>& rules, std::initializer_list<double> kds,
                        std::initializer_list<double> ratios, double max_kappa_gap,
                        bool with_gradients, const Error& error) {
  for (double kd : kds) {
    std::cout << "kappa*diameter = " << kd << "\n";
    for (double ratio : ratios) {
      if (kd * (ratio - 0.6) > max_kappa_gap)
        continue;
      std::vector<double> worst(rules.size(), 0.0);
      for (const bem::Panel& p : rule_test_panels())
        for (const Vector3d& dir : target_directions(43, 1)) {
          const Vector3d x = p.centroid + ratio * p.diameter * dir;
          const double kappa = kd / p.diameter, r = ratio * p.diameter;
          const auto ref = testing::reference_panel_integrals(kappa, p, x, with_gradients, 1e-13);
          for (size_t i = 0; i < rules.size(); ++i)
            worst[i] = std::max(worst[i], error(ref, *rules[i].rule, p, x, kappa, r));
        }
      std::cout << "  ratio " << ratio << ":";
      for (size_t i = 0; i < rules.size(); ++i)
        std::cout << " " << rules[i].name << " " << worst[i];
      std::cout << "\n";
    }
  }
}

template <class Kernel>
double sum_double_layer(const Kernel& k, const std::vector<bem::Panel>& panels, const Vector3d& x) {
  double s = 0;
  for (const auto& p : panels) s += bem::integrate_panel(k, p, x).double_layer;
  return s;
}

}  // namespace

TEST_CASE("integrate_panel: values and gradients match the reference at all distances",
          "[panel_integrals]") {
  const std::vector<double> ratios = {0.6, 1.2, 1.6, 2.2, 3.0, 4.5, 7.0, 10.0, 15.0, 40.0, 200.0};
  const std::vector<double> kappa_diameters = {0.0, 0.005, 0.2, 0.6, 1.2, 2.0, 4.0, 8.0, 100.0};
  double worst_value = 0, worst_gradient = 0;
  for (const bem::Panel& p : rule_test_panels())
    for (double kd : kappa_diameters)
      for (double ratio : ratios)
        for (const Vector3d& dir : target_directions(6, 7)) {
          const Vector3d x = p.centroid + ratio * p.diameter * dir;
          const double kappa = kd / p.diameter;
          const bool grads = ratio > 1.0;  // near gradients are covered by test_polar_quadrature
          const bem::PanelIntegrals v =
              kd == 0 ? bem::integrate_panel(LaplaceKernel{}, p, x, grads)
                      : bem::integrate_panel(YukawaKernel(kappa), p, x, grads);
          const auto ref = testing::reference_panel_integrals(kappa, p, x, grads, 1e-11);
          const auto m = testing::near_field_magnitudes(p, kappa);
          INFO("kappa*diameter = " << kd << ", ratio = " << ratio << ", dir = " << dir.transpose());
          const double ev = std::max(relative_error(v.single_layer, ref.single_layer, m.single_layer),
                                     relative_error(v.double_layer, ref.double_layer, m.double_layer));
          CHECK(ev < required_accuracy);
          worst_value = std::max(worst_value, ev);
          if (!grads) continue;
          const double eg = std::max(
              relative_error(v.single_layer_gradient, ref.single_layer_gradient,
                             m.single_layer_gradient),
              relative_error(v.double_layer_gradient, ref.double_layer_gradient,
                             m.double_layer_gradient));
          CHECK(eg < required_accuracy);
          worst_gradient = std::max(worst_gradient, eg);
        }
  WARN("integrate_panel: worst relative error, values " << worst_value << ", gradients "
                                                         << worst_gradient);
}

TEST_CASE("integrate_panel: single_layer() is the single layer of integrate_panel",
          "[panel_integrals]") {
  const YukawaKernel yukawa(3.0);
  for (const bem::Panel& p : rule_test_panels())
    for (double ratio : {0.3, 2.0, 5.0, 20.0, 300.0})
      for (const Vector3d& dir : target_directions(4, 3)) {
        const Vector3d x = p.centroid + ratio * p.diameter * dir;
        // Same rule, different summation order: equal to rounding.
        CHECK(bem::single_layer(LaplaceKernel{}, p, x) ==
              Approx(bem::integrate_panel(LaplaceKernel{}, p, x).single_layer).epsilon(1e-14));
        CHECK(bem::single_layer(yukawa, p, x) ==
              Approx(bem::integrate_panel(yukawa, p, x).single_layer).epsilon(1e-14).margin(1e-300));
      }
}

TEST_CASE("integrate_panel: Yukawa entries beyond 40/kappa are exactly zero and negligible",
          "[panel_integrals]") {
  const bem::Panel p = rule_test_panels()[0];
  const double kappa = 50.0;
  const YukawaKernel G(kappa);
  const Vector3d x = p.centroid + (p.radius + 41.0 / kappa) * Vector3d(0.6, 0, 0.8);
  const auto v = bem::integrate_panel(G, p, x, true);
  CHECK(v.single_layer == 0.0);
  CHECK(v.double_layer == 0.0);
  CHECK(v.single_layer_gradient.norm() == 0.0);
  const auto ref = testing::reference_panel_integrals(kappa, p, x, false, 1e-6);
  const auto m = testing::near_field_magnitudes(p, kappa);
  CHECK(std::abs(ref.single_layer) < 1e-16 * m.single_layer);
  CHECK(std::abs(ref.double_layer) < 1e-16 * m.double_layer);
}

TEST_CASE("integrate_panel: Laplace double layer of closed polyhedra is -1, -1/2, 0",
          "[panel_integrals]") {
  const auto sphere = bem::make_panels(geometry::make_geodesic_sphere(1.0, 6));
  const auto box = bem::make_panels(
      geometry::make_box(Vector3d(-0.5, -0.3, -0.2), Vector3d(0.7, 0.4, 0.3), 0.1));
  const LaplaceKernel G{};
  for (const auto* panels : {&sphere, &box}) {
    const bem::Panel& f = (*panels)[panels->size() / 3];
    const double h = f.diameter;
    CHECK(sum_double_layer(G, *panels, Vector3d(0.01, 0.02, -0.03)) == Approx(-1.0).epsilon(1e-12));
    CHECK(sum_double_layer(G, *panels, Vector3d(3.0, 1.0, 2.0)) == Approx(0.0).margin(1e-12));
    // Principal value at a face centroid (flat there): −½.
    CHECK(sum_double_layer(G, *panels, f.centroid) == Approx(-0.5).epsilon(1e-12));
    // Just inside and outside the face, 1e-3 panel sizes away.
    CHECK(sum_double_layer(G, *panels, f.centroid - 1e-3 * h * f.normal) ==
          Approx(-1.0).epsilon(1e-11));
    CHECK(sum_double_layer(G, *panels, f.centroid + 1e-3 * h * f.normal) ==
          Approx(0.0).margin(1e-11));
    // Near a vertex of the face, inside and outside.
    const Vector3d corner = f.corners[0];
    const Vector3d inward = (Vector3d(0.1, 0.05, 0.05) - corner).normalized();
    CHECK(sum_double_layer(G, *panels, corner + 1e-3 * h * inward) == Approx(-1.0).epsilon(1e-10));
    CHECK(sum_double_layer(G, *panels, corner - 1e-3 * h * inward) == Approx(0.0).margin(1e-10));
  }
}

TEST_CASE("integrate_panel: normal derivative of the single layer is minus the double layer",
          "[panel_integrals]") {
  // n·∇_x ∫_T G dA = ∫_T G'(r)(x − y)·n/r dA = −∫_T ∂G/∂n_y dA for a flat panel: an identity
  // between two independently computed outputs in the Gauss range, by construction in the
  // polar range. Checked over all panels of a sphere for targets inside, near and outside.
  const auto sphere = bem::make_panels(geometry::make_geodesic_sphere(1.0, 4));
  const YukawaKernel G(4.0);
  for (const Vector3d& x : {Vector3d(0.2, 0.1, 0.0), Vector3d(0.0, 0.0, 0.98), Vector3d(1.5, 0, 0)})
    for (const auto& p : sphere) {
      const auto v = bem::integrate_panel(G, p, x, true);
      CHECK(p.normal.dot(v.single_layer_gradient) ==
            Approx(-v.double_layer).margin(1e-13 * std::abs(v.single_layer) + 1e-300));
    }
}

TEST_CASE("integrate_panel: invariant under translation and rotation", "[panel_integrals]") {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vector3d shift(3.5, -1.25, 0.75);
  const YukawaKernel yukawa(2.0);
  for (const bem::Panel& p : rule_test_panels()) {
    const bem::Panel q = bem::make_panel(rotation * p.corners[0] + shift,
                                         rotation * p.corners[1] + shift,
                                         rotation * p.corners[2] + shift);
    for (double ratio : {0.0, 0.01, 0.8, 2.0, 5.0, 30.0})
      for (const Vector3d& dir : target_directions(5, 11)) {
        const Vector3d x = p.centroid + ratio * p.diameter * dir;
        const Vector3d y = rotation * x + shift;
        auto check = [&](const bem::PanelIntegrals& a, const bem::PanelIntegrals& b) {
          const double scale_sl = std::abs(a.single_layer) + 1e-300;
          CHECK(std::abs(a.single_layer - b.single_layer) <= 1e-12 * scale_sl);
          CHECK(std::abs(a.double_layer - b.double_layer) <= 1e-12 * (std::abs(a.double_layer) + 1e-3));
          if (ratio == 0.0) return;  // gradients on the panel are limits, not compared
          CHECK((rotation * a.single_layer_gradient - b.single_layer_gradient).norm() <=
                1e-11 * a.single_layer_gradient.norm());
          CHECK((rotation * a.double_layer_gradient - b.double_layer_gradient).norm() <=
                1e-11 * (a.double_layer_gradient.norm() + 1e-3));
        };
        check(bem::integrate_panel(LaplaceKernel{}, p, x, true),
              bem::integrate_panel(LaplaceKernel{}, q, y, true));
        check(bem::integrate_panel(yukawa, p, x, true), bem::integrate_panel(yukawa, q, y, true));
      }
  }
}

TEST_CASE("far-field rule table: measured errors (prints the table)",
          "[.calibration][panel_integrals]") {
  // Reproduces the calibration behind far_field_rules(): worst error of each rule, relative
  // to the entry's natural magnitude area·|G^{(k)}(r)|, over three panel shapes and 43
  // directions, per distance ratio and κ·diameter.
  const std::vector<NamedRule> rules = {
      {"sym2", &bem::symmetric_triangle_rule(2)}, {"sym5", &bem::symmetric_triangle_rule(5)},
      {"sym6", &bem::symmetric_triangle_rule(6)}, {"sym8", &bem::symmetric_triangle_rule(8)},
      {"col6", &bem::collapsed_gauss_rule(6)},    {"col8", &bem::collapsed_gauss_rule(8)}};
  print_worst_errors(
      rules, {0.0, 0.01, 0.3, 0.7, 1.0, 1.5, 2.5, 5.0},
      {1.5, 2.5, 4.0, 6.0, 8.0, 12.0, 20.0, 40.0, 60.0, 150.0}, 40.0, true,
      [](const auto& ref, const bem::TriangleRule& rule, const bem::Panel& p, const Vector3d& x,
         double kappa, double r) {
        const double e = std::exp(-kappa * r) / (4 * M_PI);
        const double g0 = e / r, g1 = e * (1 + kappa * r) / (r * r), g2 = g1 * (2 + kappa * r) / r;
        const auto v = kappa == 0
                           ? bem::gauss_panel_integrals(LaplaceKernel{}, p, x, rule, true)
                           : bem::gauss_panel_integrals(YukawaKernel(kappa), p, x, rule, true);
        return std::max(
            {std::abs(v.single_layer - ref.single_layer) / (p.area * g0),
             std::abs(v.double_layer - ref.double_layer) / (p.area * g1),
             (v.single_layer_gradient - ref.single_layer_gradient).norm() / (p.area * g1),
             (v.double_layer_gradient - ref.double_layer_gradient).norm() / (p.area * g2)});
      });
}

TEST_CASE("integrate_panel: the single-precision Laplace rules are within 1e-7 with fewer points",
          "[panel_integrals]") {
  // Targets off the calibration grid (three panel shapes, seven directions): V and K within
  // kSinglePrecisionRuleAccuracy of |T|/(4πr) and |T|/(4πr²) against the adaptive reference,
  // and from η = 1.5 to 12 on fewer points than far_field_rules() takes.
  const auto rules = bem::far_field_rules(bem::kSinglePrecisionRuleAccuracy);
  double worst = 0.0;
  int fewer = 0, between = 0;
  for (const bem::Panel& p : rule_test_panels())
    for (const Vector3d& dir : target_directions(7, 3))
      for (const double ratio : {1.5, 1.8, 2.2, 2.7, 3.4, 4.0, 4.5, 5.2, 6.0, 7.0, 10.0, 30.0, 60.0, 100.0, 200.0}) {
        const double r = ratio * p.diameter;
        const Vector3d x = p.centroid + r * dir;
        const auto ref = testing::reference_panel_integrals(0.0, p, x, false, 1e-13);
        const auto v = bem::integrate_panel(LaplaceKernel{}, p, x, false, rules);
        const double v_scale = p.area / (4 * M_PI * r), k_scale = v_scale / r;
        INFO("ratio " << ratio << ", dir " << dir.transpose());
        const double e = std::max(std::abs(v.single_layer - ref.single_layer) / v_scale,
                                  std::abs(v.double_layer - ref.double_layer) / k_scale);
        CHECK(e <= bem::kSinglePrecisionRuleAccuracy);
        worst = std::max(worst, e);
        if (ratio <= 12.0) {
          const bem::TriangleRule* coarse = bem::select_far_field_rule(ratio, 0.0, rules);
          const bem::TriangleRule* standard = bem::select_far_field_rule(ratio, 0.0);
          REQUIRE(coarse != nullptr);
          REQUIRE(standard != nullptr);
          if (coarse->size() < standard->size()) ++fewer;
          ++between;
        }
      }
  CHECK(fewer == between);
  WARN("single-precision Laplace rules: worst error " << worst);
}

TEST_CASE("integrate_attenuated_panel: within the absolute accuracy of the Laplace magnitude",
          "[panel_integrals]") {
  // Targets at ratios and κ·diameter across the attenuated table's windows and off its
  // calibration grid (three panel shapes, seven directions): V within 1e−9·|T|/(4πr) and K
  // within 1e−9·|T|/(4πr²) of the adaptive reference, and the cheap rule really is used.
  int cheap = 0, checked = 0;
  for (const bem::Panel& p : rule_test_panels())
    for (const Vector3d& dir : target_directions(7, 3))
      for (const double ratio : {1.5, 1.8, 2.2, 2.7, 3.4, 4.5, 7.0})
        for (const double kd : {0.5, 1.0, 1.7, 2.8, 3.9, 5.5, 8.0}) {
          const double kappa = kd / p.diameter, r = ratio * p.diameter;
          const Vector3d x = p.centroid + r * dir;
          const YukawaKernel kernel(kappa);
          const auto ref = testing::reference_panel_integrals(kappa, p, x, false, 1e-13);
          const auto v = bem::integrate_attenuated_panel(kernel, p, x);
          const double v_scale = p.area / (4 * M_PI * r), k_scale = v_scale / r;
          CHECK(std::abs(v.single_layer - ref.single_layer) <=
                bem::kAttenuatedRuleAccuracy * v_scale);
          CHECK(std::abs(v.double_layer - ref.double_layer) <=
                bem::kAttenuatedRuleAccuracy * k_scale);
          const bem::TriangleRule* rule = bem::select_attenuated_rule(ratio, kd);
          const bem::TriangleRule* standard = bem::select_far_field_rule(ratio, kd);
          if (rule != nullptr && (standard == nullptr || rule->size() < standard->size()))
            ++cheap;
          ++checked;
        }
  CHECK(checked == 3 * 7 * 7 * 7);
  CHECK(cheap > checked / 2);
}

TEST_CASE(
    "attenuated Yukawa rules: measured errors against the unattenuated magnitude "
    "(prints the table)",
    "[.calibration][panel_integrals]") {
  // Reproduces the calibration behind attenuated_far_field_rules(): worst error of V and K
  // of each rule, relative to the Laplace magnitude at the same distance, area/(4πr) and
  // area/(4πr²), over three panel shapes and 43 directions, per distance ratio and
  // κ·diameter. That is the scale of the Galerkin rows' largest entries, against which an
  // attenuated Yukawa entry is judged (YukawaAttenuation::absolute_accuracy).
  const std::vector<NamedRule> rules = {
      {"sym6", &bem::symmetric_triangle_rule(6)}, {"sym8", &bem::symmetric_triangle_rule(8)},
      {"col5", &bem::collapsed_gauss_rule(5)},    {"col6", &bem::collapsed_gauss_rule(6)},
      {"col7", &bem::collapsed_gauss_rule(7)},    {"col8", &bem::collapsed_gauss_rule(8)}};
  print_worst_errors(
      rules, {1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0, 8.0}, {1.5, 2.0, 2.5, 3.0, 4.0, 6.0},
      std::numeric_limits<double>::infinity(), false,
      [](const auto& ref, const bem::TriangleRule& rule, const bem::Panel& p, const Vector3d& x,
         double kappa, double r) {
        const double v_scale = p.area / (4 * M_PI * r), k_scale = v_scale / r;
        const auto v = bem::gauss_panel_integrals(YukawaKernel(kappa), p, x, rule, false);
        return std::max(std::abs(v.single_layer - ref.single_layer) / v_scale,
                        std::abs(v.double_layer - ref.double_layer) / k_scale);
      });
}

TEST_CASE(
    "gauss_panel_integrals: the array evaluation of large rules equals the sum point by point",
    "[panel_integrals]") {
  // Every rule of 12 points or more that far_field_rules() or the attenuated class uses, on
  // three panel shapes and targets in several directions and distances; the reference is
  // the definition Σ w_q G(r_q) and Σ w_q ∂G/∂n_y written out here with the kernels' scalar
  // values.
  const std::vector<const bem::TriangleRule*> rules = {
      &bem::symmetric_triangle_rule(6), &bem::symmetric_triangle_rule(8),
      &bem::collapsed_gauss_rule(4), &bem::collapsed_gauss_rule(6), &bem::collapsed_gauss_rule(8)};
  const auto check = [&](const auto& kernel) {
    int checked = 0;
    for (const bem::Panel& panel : rule_test_panels())
      for (const Vector3d& dir : target_directions(7, 5))
        for (const double distance : {1.6, 3.0, 9.0})
          for (const bem::TriangleRule* rule : rules) {
            REQUIRE(rule->size() >= bem::kArrayRulePoints);
            const Vector3d x = panel.centroid + distance * panel.diameter * dir;
            double sl = 0.0, dl = 0.0;
            for (int q = 0; q < rule->size(); ++q) {
              const auto i = static_cast<size_t>(q);
              const Vector3d y = panel.corners[0] + rule->xi[i] * panel.edge1 + rule->eta[i] * panel.edge2;
              const double r = (x - y).norm();
              sl += rule->weight[i] * kernel.value(r);
              // ∂G/∂n_y = G'(r) (y − x)·n / r
              dl += rule->weight[i] * kernel.radial_derivative(r) * (y - x).dot(panel.normal) / r;
            }
            const bem::PanelIntegrals p = bem::gauss_panel_integrals(kernel, panel, x, *rule, false);
            CHECK(p.single_layer == Approx(panel.area * sl).epsilon(1e-13));
            CHECK(p.double_layer == Approx(panel.area * dl).epsilon(1e-12).margin(1e-15 * std::abs(panel.area * sl)));
            ++checked;
          }
    CHECK(checked == 3 * 7 * 3 * 5);
  };
  check(LaplaceKernel{});
  check(YukawaKernel{2.0});
}

TEST_CASE("integrate_attenuated_panel: near targets of panels many 1/kappa across",
          "[panel_integrals]") {
  // Where no Gauss rule applies (targets within 1.5 diameters, κ·diameter up to 100) the
  // polar scheme runs at the accuracy the attenuation leaves: V within 1e−9·|T|/(4πr) and K
  // within 1e−9·|T|/(4πr²) of the polar scheme at full accuracy (itself checked against the
  // adaptive reference in test_polar_quadrature.cpp), and targets whose panel lies more than
  // about 21/κ away take no work at all.
  int zero = 0, checked = 0;
  for (const bem::Panel& p : rule_test_panels())
    for (const Vector3d& dir : target_directions(11, 5))
      for (const double ratio : {0.05, 0.3, 0.6, 0.9, 1.2, 1.45})
        for (const double kd : {4.0, 12.0, 35.0, 100.0}) {
          const double kappa = kd / p.diameter, r = ratio * p.diameter;
          const Vector3d x = p.centroid + r * dir;
          const YukawaKernel kernel(kappa);
          const auto full = bem::polar_panel_integrals(kernel, p, x, false);
          const auto v = bem::integrate_attenuated_panel(kernel, p, x);
          const double v_scale = p.area / (4 * M_PI * r), k_scale = v_scale / r;
          INFO("ratio " << ratio << ", kappa*diameter " << kd);
          CHECK(std::abs(v.single_layer - full.single_layer) <=
                bem::kAttenuatedRuleAccuracy * v_scale);
          CHECK(std::abs(v.double_layer - full.double_layer) <=
                bem::kAttenuatedRuleAccuracy * k_scale);
          if (v.single_layer == 0.0 && v.double_layer == 0.0) ++zero;
          ++checked;
        }
  CHECK(checked == 3 * 11 * 6 * 4);
  CHECK(zero > 0);
}
