#pragma once
// The one entry point the operator assembly calls: the integrals of a kernel over one flat
// panel with unit density, for one target x (definitions and sign conventions in
// bem/quadrature/panel_integral_values.hpp).
//
// Rule selection, by the distance ratio η = |x − centroid| / diameter (diameter = longest edge)
// and, for Yukawa, κ·diameter (docs/quadrature.md gives the measured errors behind every
// threshold in far_field_thresholds):
//  * Yukawa and |x − centroid| − radius > 40/κ: every entry is below e^{−40} ≈ 4e−18 of the
//    panel's near-field magnitude and is returned as exactly 0 (YukawaKernel::
//    negligible_exponent);
//  * η below the smallest threshold, or κ·diameter too large for a polynomial rule: for
//    Laplace the closed forms of bem/quadrature/laplace_triangle_potentials.hpp (75–85 ns
//    against the polar scheme's 500–660 on a 2-core Zen 3), for Yukawa the polar scheme
//    (bem/quadrature/polar_quadrature.hpp), exact radial integrals; both valid on and near
//    the panel (exact_panel_integrals);
//  * otherwise a Gauss rule on the triangle (bem/quadrature/triangle_quadrature.hpp) whose degree
//    decreases as η grows, chosen so that the relative error stays below 1e−8.
// Kernel ∈ {LaplaceKernel, YukawaKernel}.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include <Eigen/Core>

#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integral_values.hpp"
#include "bem/quadrature/laplace_triangle_potentials.hpp"
#include "bem/quadrature/polar_quadrature.hpp"
#include "bem/kernels/radial_values.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"
#include "linalg/vector_exponential.hpp"

namespace bemshape::bem {

/// One row of the far-field rule table: the rule is accurate to 1e−8 (relative) for every
/// target with η ≥ min_ratio and, for Yukawa, κ·diameter ≤ max_kappa_diameter.
struct FarFieldRule {
  double min_ratio;
  double max_kappa_diameter;
  const TriangleRule* rule;
  double min_ratio_squared() const { return min_ratio * min_ratio; }
};

/// The table, cheapest rule first. Built once.
const std::array<FarFieldRule, 7>& far_field_rules();

/// The accuracy of single_precision_far_field_rules(), relative as far_field_rules()' 1e−8.
inline constexpr double kSinglePrecisionRuleAccuracy = 1e-7;

/// The Laplace table (κ·diameter 0 only) for entries stored in single precision, whose
/// rounding (6e−8) and the factors' (about 4e−7 of a product, bem/hmatrix) leave nothing of a
/// tighter rule: each row within 1e−7 in its range, about half the points of far_field_rules()
/// from η = 1.5 to 12. Built once.
const std::array<FarFieldRule, 5>& single_precision_far_field_rules();

/// far_field_rules(), or for Laplace at `accuracy` ≥ kSinglePrecisionRuleAccuracy
/// single_precision_far_field_rules().
std::span<const FarFieldRule> far_field_rules(double accuracy);

/// The Gauss rule of `rules` (far_field_rules() by default) for distance ratio η = ratio and
/// κ·diameter (0 for Laplace), or nullptr when the polar scheme is needed.
inline const TriangleRule* select_far_field_rule(
    double ratio, double kappa_diameter, std::span<const FarFieldRule> rules = far_field_rules()) {
  for (const FarFieldRule& row : rules)
    if (ratio >= row.min_ratio && kappa_diameter <= row.max_kappa_diameter)
      return row.rule;
  return nullptr;
}

/// The same selection from squared distance and squared diameter (no square root, no division:
/// the far-field hot path).
inline const TriangleRule* select_far_field_rule_squared(double distance_squared,
                                                         double diameter_squared,
                                                         double kappa_diameter) {
  for (const FarFieldRule& row : far_field_rules())
    if (distance_squared >= row.min_ratio_squared() * diameter_squared &&
        kappa_diameter <= row.max_kappa_diameter)
      return row.rule;
  return nullptr;
}

/// The accuracy of integrate_attenuated_panel, relative to the Laplace magnitude at the same
/// distance: one digit below the 1e−8 the far-field rules keep relative to the entry itself.
inline constexpr double kAttenuatedRuleAccuracy = 1e-9;

/// One row of the attenuated Yukawa rule table: the rule keeps V within
/// kAttenuatedRuleAccuracy · |T|/(4πr) and K within kAttenuatedRuleAccuracy · |T|/(4πr²)
/// (r = |x − centroid|) for every target with η ≥ min_ratio and κ·diameter in
/// [min_kappa_diameter, max_kappa_diameter]. Those scales are the kernel's without e^{−κr}:
/// the rule may be as much less accurate relative to the entry itself as e^{−κr} is small,
/// which is what makes it cheaper than far_field_rules()' rule for the same target.
struct AttenuatedRule {
  double min_ratio;
  double min_kappa_diameter;
  double max_kappa_diameter;
  const TriangleRule* rule;
};

/// The table, cheapest rule first. Built once.
const std::array<AttenuatedRule, 7>& attenuated_far_field_rules();

/// The attenuated table at kSinglePrecisionRuleAccuracy (1e−7) instead of
/// kAttenuatedRuleAccuracy, for entries stored in single precision: 12 points from η = 2.5,
/// 16 from 2, 36 from 1.5 (κ·diameter 1–8), where the table above takes up to 49. Built once.
const std::array<AttenuatedRule, 3>& single_precision_attenuated_rules();

/// attenuated_far_field_rules(), or at `accuracy` ≥ kSinglePrecisionRuleAccuracy
/// single_precision_attenuated_rules().
std::span<const AttenuatedRule> attenuated_rules(double accuracy);

/// The rule of `rules` (attenuated_far_field_rules() by default) for distance ratio η = ratio
/// and κ·diameter, or nullptr where no row applies.
inline const TriangleRule* select_attenuated_rule(
    double ratio, double kappa_diameter,
    std::span<const AttenuatedRule> rules = attenuated_far_field_rules()) {
  for (const AttenuatedRule& row : rules)
    if (ratio >= row.min_ratio && kappa_diameter >= row.min_kappa_diameter &&
        kappa_diameter <= row.max_kappa_diameter)
      return row.rule;
  return nullptr;
}

/// The two sums a quadrature rule needs for both kernels, G = E(r)/(4πr) with E = 1
/// (Laplace) or e^{−κr} (Yukawa), so that −G'(r)/r = E(r)(1 + κr)/(4πr³): over points at
/// distances r_q with weights w_q,
///   single = Σ_q w_q E(r_q)/r_q,   double_layer = Σ_q w_q E(r_q)(1 + κr_q)/r_q³,
/// both without the 1/(4π) (gauss_radial_sums).
struct RadialSums {
  double single = 0.0, double_layer = 0.0;
};
/// The terms of those sums per point, E(r)/r and E(r)(1 + κr)/r³, from the squared
/// distances r2: Eigen arrays, so the square roots and exponentials use the SIMD width the
/// build targets.
template <class Kernel, class Array>
[[gnu::always_inline]] inline void radial_kernel_terms(const Kernel& kernel, const Array& r2,
                                                       Array& single, Array& double_layer) {
  if constexpr (Kernel::has_exponential_decay) {
    // r first, then 1/r and e^{−κr} side by side (the division does not delay the exponential).
    const double kappa = kernel.kappa();
    const Array r = r2.sqrt();
    const Array inv_r = r.inverse();
    const Array e = linalg::vector_exp<Array>(-kappa * r);
    single = e * inv_r;
    double_layer = e * (1.0 + kappa * r) * inv_r.cube();
  } else {
    const Array inv_r = r2.rsqrt();
    single = inv_r;
    double_layer = inv_r.cube();
  }
}

/// The RadialSums of `rule` on a panel for a target at offset `a` = x − corner 0 from the
/// panel's first corner, the points being y_q − corner 0 = ξ_q e1 + η_q e2: kRulePointLanes
/// points at a time in fixed-size arrays (one register of doubles: 4 with AVX2, 8 with
/// AVX-512), each group's distance, kernel terms and weighted sums in registers; a last
/// partial group repeats the rule's last point with weight 0. Against whole-rule arrays (every
/// operation a pass over the rule's values in memory) and Eigen's exponential, this and
/// linalg/vector_exponential.hpp take the 64-point rule from 2.8 to 1.7 ns per point for
/// Laplace and from 6.2 to 4.6 for Yukawa (2-core Zen 3, `bench_panel_integrals`); eight lanes
/// on the AVX-512 family-26 EPYC take it from 0.9 to 0.55 and from 4.3 to 2.6 ns
/// (docs/benchmarks.md, "Panel integrals").
#if defined(__AVX512F__)
inline constexpr int kRulePointLanes = 8;
#else
inline constexpr int kRulePointLanes = 4;
#endif
template <class Kernel>
RadialSums gauss_radial_sums(const Kernel& kernel, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                             const TriangleRule& rule) {
  using Lanes = Eigen::Array<double, kRulePointLanes, 1>;
  const int m = rule.size();
  Lanes sum_single = Lanes::Zero(), sum_double = Lanes::Zero(), single, double_layer;
  const auto add = [&](const Lanes& xi, const Lanes& eta, const Lanes& w) {
    const Lanes dx = a.x() - xi * e1.x() - eta * e2.x();
    const Lanes dy = a.y() - xi * e1.y() - eta * e2.y();
    const Lanes dz = a.z() - xi * e1.z() - eta * e2.z();
    radial_kernel_terms(kernel, Lanes(dx.square() + dy.square() + dz.square()), single,
                        double_layer);
    sum_single += w * single;
    sum_double += w * double_layer;
  };
  int q = 0;
  for (; q + kRulePointLanes <= m; q += kRulePointLanes)
    add(Eigen::Map<const Lanes>(rule.xi.data() + q), Eigen::Map<const Lanes>(rule.eta.data() + q),
        Eigen::Map<const Lanes>(rule.weight.data() + q));
  if (q < m) {
    Lanes xi, eta, w;
    for (int l = 0; l < kRulePointLanes; ++l) {
      const auto k = static_cast<std::size_t>(std::min(q + l, m - 1));
      xi(l) = rule.xi[k];
      eta(l) = rule.eta[k];
      w(l) = q + l < m ? rule.weight[k] : 0.0;
    }
    add(xi, eta, w);
  }
  return {sum_single.sum(), sum_double.sum()};
}

/// Single and double layer (and gradients) of `panel` at x by the triangle rule `rule`.
/// Accurate only for targets away from the panel (see select_far_field_rule).
///
/// Without gradients and with at least kArrayRulePoints points the sums run in SIMD lanes
/// (gauss_radial_sums), with d = (x − c_0)·n:
///   V = |T| Σ_q w_q G(r_q),   K = |T| d Σ_q w_q E(r_q)(1 + κr_q)/(4π r_q³).
/// Smaller rules (the Laplace far field's 3 and 7 points) stay point by point.
inline constexpr int kArrayRulePoints = 12;

template <class Kernel>
PanelIntegrals gauss_panel_integrals(const Kernel& kernel, const Panel& panel,
                                     const Eigen::Vector3d& x, const TriangleRule& rule,
                                     bool with_gradients) {
  PanelIntegrals out;
  const Eigen::Vector3d a = x - panel.corners[0];
  const double d = a.dot(panel.normal);
  if (!with_gradients && rule.size() >= kArrayRulePoints) {
    const RadialSums sums = gauss_radial_sums(kernel, a, panel.edge1, panel.edge2, rule);
    out.single_layer = Kernel::inv_four_pi * panel.area * sums.single;
    out.double_layer = Kernel::inv_four_pi * panel.area * d * sums.double_layer;
    return out;
  }
  double sl = 0.0, dl_factor = 0.0;
  Eigen::Vector3d g_sl = Eigen::Vector3d::Zero(), g_dl = Eigen::Vector3d::Zero();
  for (int q = 0; q < rule.size(); ++q) {
    const auto k = static_cast<size_t>(q);
    const Eigen::Vector3d y =
        panel.corners[0] + rule.xi[k] * panel.edge1 + rule.eta[k] * panel.edge2;
    const Eigen::Vector3d diff = x - y;
    const double r = diff.norm();
    const double w = rule.weight[k];
    const RadialValues g = kernel.values(r);
    const double g1 = g.radial_derivative;
    sl += w * g.value;
    // ∂G/∂n_y = G'(r)(y − x)·n/r = −d G'(r)/r.
    dl_factor += w * g1 / r;
    if (with_gradients) {
      const double h = g1 / r;                                                    // H = G'/r
      const double dh = (kernel.second_radial_derivative(r) * r - g1) / (r * r);  // H'
      g_sl += (w * h) * diff;
      // ∇_x ∂G/∂n_y = −n H(r) − d H'(r)(x − y)/r.
      g_dl += -(w * h) * panel.normal - (w * d * dh / r) * diff;
    }
  }
  out.single_layer = panel.area * sl;
  out.double_layer = -d * panel.area * dl_factor;
  if (with_gradients) {
    out.single_layer_gradient = panel.area * g_sl;
    out.double_layer_gradient = panel.area * g_dl;
  }
  return out;
}

/// The panel integrals for targets on and near the panel, where no Gauss rule serves, exact in
/// the radial direction: for Laplace in closed form (bem/quadrature/
/// laplace_triangle_potentials.hpp), for Yukawa by the polar scheme at full resolution
/// (bem/quadrature/polar_quadrature.hpp).
template <class Kernel>
PanelIntegrals exact_panel_integrals(const Kernel& kernel, const Panel& panel,
                                     const Eigen::Vector3d& x, bool with_gradients) {
  if constexpr (Kernel::has_exponential_decay)
    return polar_panel_integrals(kernel, panel, x, with_gradients);
  else
    return laplace_triangle_potentials(panel, x, with_gradients);
}

/// Single layer, double layer and (if with_gradients) their gradients ∇_x for the panel and
/// target x, to 1e−8 relative accuracy (docs/quadrature.md), or to the accuracy of `rules`
/// (far_field_rules(accuracy)).
template <class Kernel>
PanelIntegrals integrate_panel(const Kernel& kernel, const Panel& panel, const Eigen::Vector3d& x,
                               bool with_gradients = false,
                               std::span<const FarFieldRule> rules = far_field_rules()) {
  const double dist = (x - panel.centroid).norm();
  double kappa_diameter = 0.0;
  if constexpr (Kernel::has_exponential_decay) {
    if (dist - panel.radius > kernel.cutoff_distance())
      return {};
    kappa_diameter = kernel.kappa() * panel.diameter;
  }
  const TriangleRule* rule = select_far_field_rule(dist / panel.diameter, kappa_diameter, rules);
  if (rule == nullptr) return exact_panel_integrals(kernel, panel, x, with_gradients);
  return gauss_panel_integrals(kernel, panel, x, *rule, with_gradients);
}

/// Yukawa single and double layer of `panel` at x to within kAttenuatedRuleAccuracy of the
/// Laplace magnitudes at the same distance (AttenuatedRule), no gradients: the cheapest rule
/// of attenuated_far_field_rules() for the target, else integrate_panel's rule, else the polar
/// scheme at the accuracy the attenuation e^{−κc} leaves (zero where the whole triangle is
/// too far to matter). For
/// the Galerkin entries, which are judged against their rows' largest entries
/// (GalerkinOperators, YukawaAttenuation), not against themselves.
/// `accuracy` replaces kAttenuatedRuleAccuracy in the polar scheme's requirement, and from
/// kSinglePrecisionRuleAccuracy on the attenuated table is single_precision_attenuated_rules()
/// (the standard far-field rules keep theirs): the exterior near field stored in single
/// precision asks for no more than its rounding (bem/solve/yukawa_near_field.hpp).
template <class Kernel>
PanelIntegrals integrate_attenuated_panel(const Kernel& kernel, const Panel& panel,
                                          const Eigen::Vector3d& x,
                                          double accuracy = kAttenuatedRuleAccuracy) {
  static_assert(Kernel::has_exponential_decay, "the attenuated rules are for the Yukawa kernel");
  const double dist = (x - panel.centroid).norm();
  const TriangleRule* rule = select_attenuated_rule(
      dist / panel.diameter, kernel.kappa() * panel.diameter, attenuated_rules(accuracy));
  if (dist - panel.radius > kernel.cutoff_distance()) return {};
  if (rule != nullptr) return gauss_panel_integrals(kernel, panel, x, *rule, false);
  if (const TriangleRule* standard = select_far_field_rule(dist / panel.diameter,
                                                           kernel.kappa() * panel.diameter))
    return gauss_panel_integrals(kernel, panel, x, *standard, false);
  // The polar scheme, whose cost grows with κ·diameter, needs only the accuracy the
  // attenuation leaves. With c the distance from x to the triangle itself (the bounding ball
  // above is pessimistic for panels many 1/κ across), ρ ≥ c over the panel and r ≤ c + radius
  // (r = |x − centroid|), the values are bounded by
  //   |V| ≤ B_V = e^{−κc}|T|/(4πc),   |K| ≤ B_K = e^{−κc}(1 + κc)|T|/(4πc²),
  // so errors of τ·B keep V within kAttenuatedRuleAccuracy·|T|/(4πr) and K within
  // kAttenuatedRuleAccuracy·|T|/(4πr²) for
  //   τ = kAttenuatedRuleAccuracy · e^{κc} · min(c/r, (c/r)²/(1 + κc)),
  // and with τ ≥ 1 the panel contributes nothing at that accuracy.
  const double c = distance_to_panel(panel, x);
  if (c > 0.0) {
    const double kc = kernel.kappa() * c, near = c / dist;
    const double tau = accuracy * std::exp(kc) * std::min(near, near * near / (1.0 + kc));
    if (tau >= 1.0) return {};
    return polar_panel_integrals(kernel, panel, x, false, PolarResolution::for_accuracy(tau));
  }
  return polar_panel_integrals(kernel, panel, x, false);
}

/// The single layer alone (the far-field hot path of dense and compressed assembly): same
/// rule selection and accuracy as integrate_panel, no double layer.
template <class Kernel>
double single_layer(const Kernel& kernel, const Panel& panel, const Eigen::Vector3d& x) {
  const double dist2 = (x - panel.centroid).squaredNorm();
  double kappa_diameter = 0.0;
  if constexpr (Kernel::has_exponential_decay) {
    const double reach = panel.radius + kernel.cutoff_distance();
    if (dist2 > reach * reach)
      return 0.0;
    kappa_diameter = kernel.kappa() * panel.diameter;
  }
  const TriangleRule* rule =
      select_far_field_rule_squared(dist2, panel.diameter * panel.diameter, kappa_diameter);
  if (rule == nullptr) return exact_panel_integrals(kernel, panel, x, false).single_layer;
  const Eigen::Vector3d xa = x - panel.corners[0];
  const int n = rule->size();
  const double* xi = rule->xi.data();
  const double* eta = rule->eta.data();
  const double* weight = rule->weight.data();
  double sum = 0.0;
  for (int q = 0; q < n; ++q) {
    const double r2 = (xa - xi[q] * panel.edge1 - eta[q] * panel.edge2).squaredNorm();
    if constexpr (Kernel::has_exponential_decay)
      sum += weight[q] * kernel.value(std::sqrt(r2));
    else
      sum += weight[q] / std::sqrt(r2);
  }
  if constexpr (Kernel::has_exponential_decay)
    return panel.area * sum;
  else
    return (Kernel::inv_four_pi * panel.area) * sum;
}

}  // namespace bemshape::bem
