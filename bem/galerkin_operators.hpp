#pragma once
// Galerkin entries of the boundary integral operators for piecewise-constant (P0) densities
// on flat triangles T_j (test) and T_k (trial):
//
//   V[j, k] = ∫_{T_j} ∫_{T_k} G(|x − y|) dA_y dA_x                   single layer [units³]
//   K[j, k] = ∫_{T_j} p.v. ∫_{T_k} ∂G/∂n_y(x, y) dA_y dA_x           double layer [units²]
//
// with G the Laplace kernel 1/(4πr) or the Yukawa kernel e^{−κr}/(4πr) and n_y outward. The
// inner integral is the semi-analytic panel integral of bem/panel_integrals.hpp (exact in the
// radial direction, so it is accurate for every x on or near T_k); the outer integral is a
// Gauss rule on T_j graded by the distance between the panels (kOuterRules below). On a
// flat panel the double-layer kernel vanishes on the panel itself, so K[j, j] = 0; the ±½
// jump terms are ½·|T_j| on the diagonal and are added by the caller.
//
// Why Galerkin and not collocation: the exterior (Yukawa) solution has a boundary layer of
// width 1/κ at the edges between tilted panels, narrower than the panels for the element
// sizes users want (κ·h ≈ 3–10). A collocation point at the centroid does not see it and the
// curvature of the surface is lost; testing with the whole panel does. docs/theory.md gives
// the measured comparison.
//
// Dense and compressed assembly both call `entry`/`fill`, so every path shares this code.

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "bem/panel.hpp"
#include "bem/panel_integrals.hpp"
#include "bem/triangle_quadrature.hpp"

namespace bemshape::bem {

/// Outer (test-panel) quadrature by the separation ratio η = |c_j − c_k| / max(diam_j, diam_k).
/// Thresholds chosen so that the outer rule's error stays well below the discretisation
/// error (measured on the ball, docs/theory.md): a rule of degree p on T_j integrates the
/// smooth far-field potential of T_k with relative error ~ η^{−(p+1)}.
struct OuterRuleThresholds {
  /// Below this ratio T_j is split into 4^L sub-triangles with a degree-4 rule on each, L
  /// growing with κ·diam so the 1/κ boundary layer is resolved; one level less when the
  /// panels do not touch (the trial panel's potential is then smooth on T_j).
  static constexpr double near_ratio = 2.0;
  /// Between near_ratio and this: the 6-point degree-4 rule on T_j (empty range: measured on
  /// the ball, the 3-point rule below already leaves the solution unchanged to 1e-4).
  static constexpr double middle_ratio = 2.0;
  /// Between middle_ratio and this: the 3-point degree-2 rule; beyond: the centroid. On the
  /// ball (R = 0.5, h0 = 0.3, N = 1280) moving this from 12 to 4 changed f_h by < 1e-4 and
  /// halved the assembly time.
  static constexpr double far_ratio = 4.0;
};

/// Splits triangle (a, b, c) into 4^levels congruent sub-triangles and returns the points and
/// weights of `rule` on each, weights summing to the triangle's area.
inline void subdivided_rule(const Panel& panel, int levels, const TriangleRule& rule,
                            std::vector<Eigen::Vector3d>& points, std::vector<double>& weights) {
  points.clear();
  weights.clear();
  std::vector<std::array<Eigen::Vector3d, 3>> tris{{panel.corners[0], panel.corners[1], panel.corners[2]}};
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<Eigen::Vector3d, 3>> finer;
    finer.reserve(4 * tris.size());
    for (const auto& t : tris) {
      const Eigen::Vector3d ab = 0.5 * (t[0] + t[1]), bc = 0.5 * (t[1] + t[2]), ca = 0.5 * (t[2] + t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({ab, t[1], bc});
      finer.push_back({ca, bc, t[2]});
      finer.push_back({ab, bc, ca});
    }
    tris.swap(finer);
  }
  const double sub_area = panel.area / static_cast<double>(tris.size());
  for (const auto& t : tris) {
    for (int q = 0; q < rule.size(); ++q) {
      const auto i = static_cast<size_t>(q);
      points.push_back(t[0] + rule.xi[i] * (t[1] - t[0]) + rule.eta[i] * (t[2] - t[0]));
      weights.push_back(sub_area * rule.weight[i]);
    }
  }
}

/// Yukawa entries are judged against the size of the row's largest entries, not their own:
/// an entry attenuated by s = e^{−κ·gap} (gap = the smallest possible distance between the
/// panels) needs only relative accuracy kYukawaAbsoluteAccuracy/s.
struct YukawaAttenuation {
  /// Absolute accuracy of a Yukawa entry relative to an unattenuated one: one digit below
  /// the quadrature's 1e−8 target, so dropped and cheapened entries do not show.
  static constexpr double absolute_accuracy = 1e-9;
  /// Entries attenuated below this are zero: e^{−κ·gap} < 1e−10 (gap > 23/κ).
  static constexpr double negligible = 1e-10;
  /// Below this attenuation a collapsed Gauss rule replaces integrate_panel's choice.
  static constexpr double cheap_rule = 1e-3;
};

/// Points per direction of the collapsed Gauss rule (degree 2n − 2) whose error estimate for
/// a Yukawa panel integral, s·[(κ·diam/2)^{2n−1}/(2n−1)! + ratio^{−(2n−1)}], is below
/// YukawaAttenuation::absolute_accuracy; 0 if none up to 8 points per direction is.
inline int attenuated_rule_points(double attenuation, double kappa_diameter, double ratio) {
  double taylor = 1.0;  // (κ·diam/2)^m / m!, m = 2n − 1
  const double half = 0.5 * kappa_diameter;
  int m = 0;
  for (int n = 1; n <= 8; ++n) {
    for (; m < 2 * n - 1; ++m) taylor *= half / (m + 1);
    const double estimate = attenuation * (taylor + std::pow(ratio, -(2 * n - 1)));
    if (estimate < YukawaAttenuation::absolute_accuracy) return n;
  }
  return 0;
}

template <class Kernel>
class GalerkinOperators {
 public:
  GalerkinOperators(Kernel kernel, const std::vector<Panel>& panels)
      : kernel_(kernel), panels_(&panels) {}

  struct Entry {
    double single_layer = 0.0;  ///< V[j, k]
    double double_layer = 0.0;  ///< K[j, k]
  };

  /// Levels of subdivision of the test panel for near interactions: one for Laplace and
  /// mild κ, two when the Yukawa boundary layer 1/κ is much thinner than the panel. A third
  /// level (384 outer points) changed the plate's thickness by 1e−6 relative at κ·diam = 14
  /// and cost 3.7× the assembly time, so two is the cap.
  int near_levels(const Panel& test, const Panel& trial) const {
    const double kd = kernel_.kappa() * test.diameter;
    const int levels = kd <= 4.0 ? 1 : 2;
    return touching(test, trial) ? levels : levels - 1;
  }

  /// True if the panels share a corner (corners are copies of the same mesh vertices, so
  /// shared ones compare equal exactly).
  static bool touching(const Panel& a, const Panel& b) {
    for (const auto& p : a.corners)
      for (const auto& q : b.corners)
        if (p == q) return true;
    return false;
  }

  Entry entry(Eigen::Index row, Eigen::Index col) const {
    const Panel& test = (*panels_)[static_cast<size_t>(row)];
    const Panel& trial = (*panels_)[static_cast<size_t>(col)];
    const double ratio = (test.centroid - trial.centroid).norm() /
                         std::max(test.diameter, trial.diameter);
    if constexpr (Kernel::has_exponential_decay) {
      const double gap = std::max(
          0.0, (test.centroid - trial.centroid).norm() - test.radius - trial.radius);
      const double attenuation = std::exp(-kernel_.kappa() * gap);
      if (attenuation < YukawaAttenuation::negligible) return {};
      if (attenuation < YukawaAttenuation::cheap_rule && ratio >= 1.5) {
        const int n = attenuated_rule_points(attenuation, kernel_.kappa() * trial.diameter, ratio);
        if (n > 0) return attenuated_entry(test, trial, collapsed_gauss_rule(n));
      }
    }
    if (ratio >= OuterRuleThresholds::far_ratio) {
      const PanelIntegrals p = integrate_panel(kernel_, trial, test.centroid);
      return {test.area * p.single_layer, test.area * p.double_layer};
    }
    thread_local std::vector<Eigen::Vector3d> points;
    thread_local std::vector<double> weights;
    if (ratio >= OuterRuleThresholds::middle_ratio)
      subdivided_rule(test, 0, symmetric_triangle_rule(2), points, weights);
    else if (ratio >= OuterRuleThresholds::near_ratio)
      subdivided_rule(test, 0, symmetric_triangle_rule(4), points, weights);
    else
      subdivided_rule(test, near_levels(test, trial), symmetric_triangle_rule(4), points, weights);
    Entry e;
    for (size_t q = 0; q < points.size(); ++q) {
      const PanelIntegrals p = integrate_panel(kernel_, trial, points[q]);
      e.single_layer += weights[q] * p.single_layer;
      e.double_layer += weights[q] * p.double_layer;
    }
    // A flat panel's double-layer kernel vanishes on the panel itself; zero it exactly rather
    // than let the rounding of the test points' heights pick a one-sided limit.
    if (row == col) e.double_layer = 0.0;
    return e;
  }

  /// A Yukawa entry whose attenuation allows a low-order rule: centroid of the test panel
  /// times the trial panel's Gauss integral (the outer rule's error is attenuated alike).
  Entry attenuated_entry(const Panel& test, const Panel& trial, const TriangleRule& rule) const {
    const PanelIntegrals p = gauss_panel_integrals(kernel_, trial, test.centroid, rule, false);
    return {test.area * p.single_layer, test.area * p.double_layer};
  }

  /// Fills V(r, c) and K(r, c) for rows[r], cols[c] (both pre-sized |rows|×|cols|).
  void fill(std::span<const Eigen::Index> rows, std::span<const Eigen::Index> cols,
            Eigen::Ref<Eigen::MatrixXd> single_layer, Eigen::Ref<Eigen::MatrixXd> double_layer) const {
    for (size_t c = 0; c < cols.size(); ++c) {
      for (size_t r = 0; r < rows.size(); ++r) {
        const Entry e = entry(rows[r], cols[c]);
        single_layer(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = e.single_layer;
        double_layer(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = e.double_layer;
      }
    }
  }

  Eigen::Index size() const { return static_cast<Eigen::Index>(panels_->size()); }
  const Kernel& kernel() const { return kernel_; }

 private:
  Kernel kernel_;
  const std::vector<Panel>* panels_;
};

}  // namespace bemshape::bem
