#pragma once
// Galerkin entries of the boundary integral operators for piecewise-constant (P0) densities
// on flat triangles T_j (test) and T_k (trial):
//
//   V[j, k] = ∫_{T_j} ∫_{T_k} G(|x − y|) dA_y dA_x                   single layer [units³]
//   K[j, k] = ∫_{T_j} p.v. ∫_{T_k} ∂G/∂n_y(x, y) dA_y dA_x           double layer [units²]
//
// with G the Laplace kernel 1/(4πr) or the Yukawa kernel e^{−κr}/(4πr) and n_y outward.
// Panels that share a corner (the singular pairs) are integrated in 4-D by the Sauter–Schwab
// rules of bem/quadrature/sauter_schwab_rules.hpp. For all others the inner integral is the
// semi-analytic panel integral of bem/quadrature/panel_integrals.hpp (exact in the radial direction, so
// it is accurate for every x near T_k) and the outer integral a Gauss rule on T_j graded by
// the distance between the panels (OuterRuleThresholds below). On a flat panel the double-layer kernel vanishes on the panel itself, so K[j, j] = 0; the ±½
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
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "bem/operators/far_field_lanes.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/operators/panel_arrays.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/quadrature/radial_moments.hpp"
#include "bem/kernels/radial_values.hpp"
#include "bem/quadrature/sauter_schwab_rules.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"
#include "core/assert.hpp"
#include "core/cancellation.hpp"

namespace bemshape::bem {

/// Two touching panels are coplanar when every edge of each is orthogonal to the other's
/// normal to this fraction of the longest edge: their double-layer entries then vanish (the
/// kernel's n·(x − y) is zero on the pair), are set to exactly 0, and the Sauter–Schwab loop
/// sums V alone.
inline constexpr double kCoplanarTouchingTolerance = 1e-12;

/// Outer (test-panel) quadrature by the separation ratio η = |c_j − c_k| / max(diam_j, diam_k).
/// Thresholds chosen so that the outer rule's error stays well below the discretisation
/// error (measured on the ball, docs/theory.md): a rule of degree p on T_j integrates the
/// smooth far-field potential of T_k with relative error ~ η^{−(p+1)}.
struct OuterRuleThresholds {
  /// Below this ratio the pairs that do not touch take the outer rule of
  /// GalerkinOperators::near_outer_rule (more points where κ·diameter is large, so that the
  /// fall-off of the trial panel's potential across T_j is integrated).
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
  if (levels == 0) {  // the rule on the panel itself: no sub-triangles to build
    for (int q = 0; q < rule.size(); ++q) {
      const auto i = static_cast<size_t>(q);
      points.push_back(panel.corners[0] + rule.xi[i] * panel.edge1 + rule.eta[i] * panel.edge2);
      weights.push_back(panel.area * rule.weight[i]);
    }
    return;
  }
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
/// panels) needs only relative accuracy absolute_accuracy/s.
struct YukawaAttenuation {
  /// Absolute accuracy of a Yukawa entry relative to an unattenuated one: one digit below
  /// the quadrature's 1e−8 target, so dropped and cheapened entries do not show. The
  /// attenuated rule table of bem/quadrature/panel_integrals.hpp keeps the same accuracy.
  static constexpr double absolute_accuracy = kAttenuatedRuleAccuracy;
  /// Entries attenuated below this are zero: e^{−κ·gap} < 1e−10 (gap > 23/κ).
  static constexpr double negligible = 1e-10;
  /// Below this attenuation a collapsed Gauss rule replaces integrate_panel's choice.
  static constexpr double cheap_rule = 1e-3;
};

/// Points per direction of the collapsed Gauss rule (degree 2n − 2) whose error estimate for
/// a Yukawa panel integral, s·[(κ·diam/2)^{2n−1}/(2n−1)! + ratio^{−(2n−1)}], is below
/// `accuracy` (YukawaAttenuation::absolute_accuracy unless the entries are stored more
/// coarsely); 0 if none up to 8 points per direction is.
inline int attenuated_rule_points(double attenuation, double kappa_diameter, double ratio,
                                  double accuracy = YukawaAttenuation::absolute_accuracy) {
  double taylor = 1.0;  // (κ·diam/2)^m / m!, m = 2n − 1
  const double half = 0.5 * kappa_diameter;
  const double inverse_ratio = 1.0 / ratio;
  double inverse_power = inverse_ratio;  // ratio^−(2n−1), by products (no pow per entry)
  int m = 0;
  for (int n = 1; n <= 8; ++n) {
    for (; m < 2 * n - 1; ++m) taylor *= half / (m + 1);
    const double estimate = attenuation * (taylor + inverse_power);
    if (estimate < accuracy) return n;
    inverse_power *= inverse_ratio * inverse_ratio;
  }
  return 0;
}

/// How two touching panels meet, and their corners reordered for bem/quadrature/sauter_schwab_rules.hpp:
/// shared corners first, in the same order in both panels.
struct TouchingOrder {
  TouchingKind kind;
  std::array<int, 3> test, trial;  ///< corner indices into Panel::corners
};

/// The touching order of two panels that share one, two or three corners (compared exactly:
/// corners are copies of the same mesh vertices); nullopt if they share none.
inline std::optional<TouchingOrder> touching_order(const Panel& test, const Panel& trial) {
  std::array<int, 3> shared_test{}, shared_trial{};
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (test.corners[size_t(i)] == trial.corners[size_t(j)]) {
        shared_test[size_t(shared)] = i;
        shared_trial[size_t(shared)] = j;
        ++shared;
        break;
      }
  if (shared == 0) return std::nullopt;
  if (shared == 3) return TouchingOrder{TouchingKind::coincident, shared_test, shared_trial};
  // Complete both orders with the corners not shared, in increasing index order.
  const auto complete = [shared](std::array<int, 3> order) {
    int next = shared;
    for (int c = 0; c < 3; ++c)
      if (std::find(order.begin(), order.begin() + shared, c) == order.begin() + shared)
        order[size_t(next++)] = c;
    return order;
  };
  return TouchingOrder{shared == 2 ? TouchingKind::common_edge : TouchingKind::common_vertex,
                       complete(shared_test), complete(shared_trial)};
}

/// Gauss points per remaining direction of the Sauter–Schwab rule for a touching pair of
/// `kind` (bem/quadrature/sauter_schwab_rules.hpp: coincident 6n, edge 5n², vertex 2n³
/// points). The direction of x − y is exact (bem/quadrature/radial_moments.hpp), so the
/// errors do not grow with κ·diameter and one n per kind serves every kernel. Measured against
/// the 16-point limit on a sphere mesh and on the right-angled edges and corners of a box at
/// κ·diameter 0–150 (tests/bem/quadrature/test_sauter_schwab_rules.cpp, docs/quadrature.md):
/// within 2e−8 of the row's diagonal entry V_jj in V and within 9e−7·V_jj/diameter in K,
/// an entry's error counting in proportion to the row it perturbs, not to its own size.
/// (Coincident pairs cost 6n evaluations: 12 points keep the right-angled ones' row sums
/// on a plane within 1e−9 where 8 left 5e−7.)
constexpr int touching_rule_points(TouchingKind kind) {
  return kind == TouchingKind::coincident ? 12 : kind == TouchingKind::common_edge ? 8 : 7;
}

template <class Kernel>
class GalerkinOperators {
 public:
  /// Operators on `panels` (kept by reference). `faces`, if given, holds the mesh face
  /// number of each panel (the H-matrix path keeps its panels in cluster-tree order); it
  /// orients the touching pairs' rules, so that each pair is integrated the same way in every
  /// panel order. Without it panel i is face i.
  GalerkinOperators(Kernel kernel, const std::vector<Panel>& panels,
                    const std::vector<Eigen::Index>* faces = nullptr)
      : kernel_(kernel),
        panels_(&panels),
        faces_(faces),
        arrays_(panels) {}

  struct Entry {
    double single_layer = 0.0;  ///< V[j, k]
    double double_layer = 0.0;  ///< K[j, k]
  };

  /// The outer rule on the test panel of near pairs that do not touch (η < near_ratio): the
  /// 6-point degree-4 rule for Laplace and mild κ, the 12-point degree-6 rule when the Yukawa
  /// boundary layer 1/κ is much thinner than the panel (κ·diameter > 4), where the trial
  /// panel's potential falls off across the test panel like e^{−κ·dist}. Measured on a plane
  /// meshed with κ·diameter ≈ 7 (tests/bem/operators/test_galerkin_operators.cpp, the row sums
  /// of Vκ against 1/(2κ)): worst relative error 9e−7 with the 12-point rule, 7e−7 with the 24
  /// points of the degree-4 rule on four sub-triangles (twice the cost), 1.4e−6 with the 6-point
  /// rule; the walls read on the labelled parts did not change to six digits. (Touching pairs
  /// use the Sauter–Schwab rules instead.) Beyond κ·diameter = 12 the 6-point rule is again
  /// enough: the trial panel's potential has fallen off within a small part of the test
  /// panel's area, and the same row sums are within 2e−8 with it at κ·diameter 21, 42 and 71
  /// (the tests ask for 1e−7 and 5e−8; there the rows are mostly touching pairs). The exterior
  /// near field of the 356 mm tray of bench/bench_thickness_tools (panels up to κ·diameter
  /// 40): 15.0–15.3 → 12.3 s, its readings unchanged; plate_holes' panels are mostly below 12.
  const TriangleRule& near_outer_rule(const Panel& test) const {
    const double kappa_diameter = kernel_.kappa() * test.diameter;
    return symmetric_triangle_rule(kappa_diameter <= 4.0 || kappa_diameter > 12.0 ? 4 : 6);
  }

  /// The outer rule of a Yukawa pair that does not touch, with η < near_ratio: where the test
  /// panel is small against its gap to the trial panel, g = (distance from the test panel's
  /// centroid to the trial panel) − (the test panel's radius), the trial panel's potential is
  /// smooth across the test panel on the scale of g and fewer points integrate it: g ≥
  /// kThreePointGap diameters of the test panel the 3-point degree-2 rule, g ≥ kSixPointGap the
  /// 6-point degree-4 rule; nearer, near_outer_rule(test). Against the 12-point rule on four
  /// sub-triangles, over the near pairs with g ≥ 1 diameter of 600 rows of the solver meshes
  /// of plate_holes and the 356 mm tray of bench/bench_thickness_tools: worst error 2.3e−6 of
  /// the row's largest V (K against ½|T_j|, its jump); the 3-point rule from g ≥ 2 diameters
  /// would leave 9.2e−6. Between 0.5 and 1 diameter (against the 12-point rule on 16
  /// sub-triangles, 300 rows of each) the 6-point rule leaves at most 6.4e−6, the error it
  /// already left there where κ·diameter < 4; from g ≥ 0.5 instead of 0.75 it would take 5 %
  /// more off the tray's near pairs, but the row sums of Vκ on the plane at κ·diameter 7 then
  /// miss 1/(2κ) by 1.7e−6, where the test asks for 1e−6. Nearer than half a diameter every
  /// rule leaves more (up to 1e−4 with 12 points on the tray, κ·diameter 8–24).
  /// tests/bem/operators/test_galerkin_operators.cpp checks a small panel beside and above a
  /// large one.
  static constexpr double kSixPointGap = 0.75;
  static constexpr double kThreePointGap = 3.0;
  const TriangleRule& near_outer_rule(const Panel& test, const Panel& trial) const {
    if constexpr (Kernel::has_exponential_decay) {
      const double gap = distance_to_panel(trial, test.centroid) - test.radius;
      if (gap >= kThreePointGap * test.diameter) return symmetric_triangle_rule(2);
      if (gap >= kSixPointGap * test.diameter) return symmetric_triangle_rule(4);
    }
    return near_outer_rule(test);
  }

  /// True if the panels share a corner (corners are copies of the same mesh vertices, so
  /// shared ones compare equal exactly).
  static bool touching(const Panel& a, const Panel& b) { return touching_order(a, b).has_value(); }

  /// The accuracy of the Yukawa entries that do not touch, relative to an unattenuated entry:
  /// of the trial panel's integrals at the outer rule points (integrate_attenuated_panel: the
  /// polar scheme, and from kSinglePrecisionRuleAccuracy on the attenuated Gauss rules too) and
  /// of the collapsed rules of attenuated pairs (attenuated_rule_points);
  /// YukawaAttenuation::absolute_accuracy unless an assembly that stores its entries more
  /// coarsely asks for less. The touching pairs and the outer rules keep theirs.
  void set_yukawa_accuracy(double accuracy) { yukawa_accuracy_ = accuracy; }

  /// The accuracy of the Laplace panel integrals at the outer rule points, relative to each
  /// integral: 1e−8 (far_field_rules()), or from kSinglePrecisionRuleAccuracy on the cheaper
  /// rules of an assembly that stores its entries in single precision
  /// (far_field_rules(accuracy)). No effect on Yukawa.
  void set_laplace_accuracy(double accuracy) { laplace_rules_ = far_field_rules(accuracy); }

  Entry entry(Eigen::Index row, Eigen::Index col) const {
    const Panel& test = (*panels_)[static_cast<size_t>(row)];
    const Panel& trial = (*panels_)[static_cast<size_t>(col)];
    const double ratio = separation_ratio(test, trial);
    // Panels sharing a corner have centroids at most 4/3 of the larger diameter apart (each
    // centroid lies within 2/3 of a median of the shared corner), so only near pairs can touch:
    // the far field, most of the calls, skips the corner comparison.
    if (ratio < OuterRuleThresholds::near_ratio) {
      if (!touching_offsets_.empty()) {
        // Tabulated: every touching pair is in the table, so a pair not found does not touch.
        for (auto s = touching_offsets_[size_t(row)]; s < touching_offsets_[size_t(row) + 1]; ++s)
          if (touching_columns_[size_t(s)] == col) return touching_entries_[size_t(s)];
      } else if (touching(test, trial)) {
        return touching_entry(row, col);
      }
    }
    if constexpr (Kernel::has_exponential_decay) {
      const int n = attenuated_points(test, trial, ratio);
      if (n < 0) return {};
      if (n > 0) return attenuated_entry(test, trial, collapsed_gauss_rule(n));
    }
    if (ratio >= OuterRuleThresholds::far_ratio) {
      const PanelIntegrals p = trial_integrals(trial, test.centroid);
      return {test.area * p.single_layer, test.area * p.double_layer};
    }
    if (ratio >= OuterRuleThresholds::middle_ratio)
      return outer_rule_entry(test, trial, 0, symmetric_triangle_rule(2));
    if (ratio >= OuterRuleThresholds::near_ratio)
      return outer_rule_entry(test, trial, 0, symmetric_triangle_rule(4));
    return outer_rule_entry(test, trial, 0, near_outer_rule(test, trial));
  }

  /// The separation ratio η = |c_j − c_k| / max(diam_j, diam_k) that selects entry()'s rules.
  static double separation_ratio(const Panel& test, const Panel& trial) {
    return (test.centroid - trial.centroid).norm() / std::max(test.diameter, trial.diameter);
  }

  /// For a Yukawa pair that does not touch: −1 if its entries are negligible (zero), n > 0 if
  /// attenuation allows the collapsed n × n Gauss rule (attenuated_entry), 0 if entry()'s
  /// other rules are needed. Touching pairs (gap 0) get 0. entry() and fill_row both decide
  /// here, so they decide alike.
  int attenuated_points(const Panel& test, const Panel& trial, double ratio) const {
    const double gap =
        std::max(0.0, (test.centroid - trial.centroid).norm() - test.radius - trial.radius);
    const double attenuation = std::exp(-kernel_.kappa() * gap);
    if (attenuation < YukawaAttenuation::negligible) return -1;
    if (attenuation < YukawaAttenuation::cheap_rule && ratio >= 1.5)
      return attenuated_rule_points(attenuation, kernel_.kappa() * trial.diameter, ratio,
                                    std::max(yukawa_accuracy_, YukawaAttenuation::absolute_accuracy));
    return 0;
  }

  /// The entries (row, cols[i]) into out[i], as `entry` gives them. For Yukawa the attenuated
  /// pairs are computed kFarFieldLanes at a time, grouped by their rule
  /// (bem/operators/far_field_lanes.hpp); the others one at a time.
  void fill_row(Eigen::Index row, std::span<const Eigen::Index> cols, std::span<Entry> out) const {
    if constexpr (!Kernel::has_exponential_decay) {
      for (size_t i = 0; i < cols.size(); ++i) out[i] = entry(row, cols[i]);
    } else {
      constexpr int kMaxPoints = 8;  // attenuated_rule_points returns at most 8
      thread_local std::array<std::vector<size_t>, kMaxPoints + 1> by_points;
      for (auto& positions : by_points) positions.clear();
      const Panel& test = (*panels_)[size_t(row)];
      for (size_t i = 0; i < cols.size(); ++i) {
        const Panel& trial = (*panels_)[size_t(cols[i])];
        const int n = attenuated_points(test, trial, separation_ratio(test, trial));
        if (n > 0)
          by_points[size_t(n)].push_back(i);
        else
          out[i] = n < 0 ? Entry{} : entry(row, cols[i]);
      }
      const PanelLanes test_lanes = PanelLanes::repeated(arrays_, row);
      std::array<Eigen::Index, kFarFieldLanes> lanes{};
      for (int n = 1; n <= kMaxPoints; ++n) {
        const auto& positions = by_points[size_t(n)];
        const TriangleRule& rule = collapsed_gauss_rule(n);
        for (size_t begin = 0; begin < positions.size(); begin += kFarFieldLanes) {
          const size_t count = std::min<size_t>(kFarFieldLanes, positions.size() - begin);
          // A short last group repeats its last pair in the spare lanes.
          for (size_t l = 0; l < size_t(kFarFieldLanes); ++l)
            lanes[l] = cols[positions[begin + std::min(l, count - 1)]];
          const FarFieldEntries e = yukawa_attenuated_lanes(
              test_lanes, PanelLanes::gathered(arrays_, lanes), kernel_.kappa(), rule);
          for (size_t l = 0; l < count; ++l)
            out[positions[begin + l]] = {e.single_layer(Eigen::Index(l)), e.double_layer(Eigen::Index(l))};
        }
      }
    }
  }

  /// The trial panel's single and double layer at an outer rule point x: for Yukawa to
  /// YukawaAttenuation::absolute_accuracy of an unattenuated entry, its polar integrals to
  /// set_yukawa_accuracy's (integrate_attenuated_panel), for Laplace to 1e−8 of the entry or
  /// set_laplace_accuracy's (integrate_panel).
  PanelIntegrals trial_integrals(const Panel& trial, const Eigen::Vector3d& x) const {
    if constexpr (Kernel::has_exponential_decay)
      return integrate_attenuated_panel(kernel_, trial, x, yukawa_accuracy_);
    else
      return integrate_panel(kernel_, trial, x, false, laplace_rules_);
  }

  /// The entry by `rule` on T_j split into 4^levels sub-triangles, times the panel integrals
  /// of T_k at each point (exact in the radial direction, bem/quadrature/panel_integrals.hpp): the
  /// scheme of the near pairs that do not touch, and with many levels the reference the tests
  /// check the touching rules against. For touching pairs it converges slowly (the potential
  /// of T_k has logarithmic derivatives at its edges), which is why entry() does not use it
  /// for them.
  Entry outer_rule_entry(const Panel& test, const Panel& trial, int levels,
                         const TriangleRule& rule) const {
    thread_local std::vector<Eigen::Vector3d> points;
    thread_local std::vector<double> weights;
    subdivided_rule(test, levels, rule, points, weights);
    Entry e;
    for (size_t q = 0; q < points.size(); ++q) {
      const PanelIntegrals p = trial_integrals(trial, points[q]);
      e.single_layer += weights[q] * p.single_layer;
      e.double_layer += weights[q] * p.double_layer;
    }
    // A flat panel's double-layer kernel vanishes on the panel itself; zero it exactly rather
    // than let the rounding of the test points' heights pick a one-sided limit.
    if (&test == &trial) e.double_layer = 0.0;
    return e;
  }

  /// The entry of two touching panels, from the pair's Sauter–Schwab rule in its canonical
  /// orientation (the panel of smaller face number is the test panel, see the constructor):
  /// (j, k) and (k, j) come from the same rule points, so V[j, k] = V[k, j] exactly, and
  /// every path (dense, H-matrix in tree order) computes the same values.
  Entry touching_entry(Eigen::Index row, Eigen::Index col) const {
    const bool forward = face(row) <= face(col);
    const Panel& first = (*panels_)[size_t(forward ? row : col)];
    const Panel& second = (*panels_)[size_t(forward ? col : row)];
    const TouchingPairEntries e = touching_pair(first, second);
    return {e.single_layer, forward ? e.double_layer : e.double_layer_transposed};
  }

  /// V[j, k] = V[k, j], K[j, k] and K[k, j] of a touching pair (test T_j, trial T_k).
  struct TouchingPairEntries {
    double single_layer = 0.0, double_layer = 0.0, double_layer_transposed = 0.0;
  };

  /// The pair's entries by its Sauter–Schwab rule, n points per direction chosen by
  /// touching_rule_points.
  TouchingPairEntries touching_pair(const Panel& test, const Panel& trial) const {
    const auto order = touching_order(test, trial);
    BEMSHAPE_ASSERT(order.has_value(), "touching_pair: the panels share no corner");
    return touching_pair(test, trial, *order,
                         sauter_schwab_rule(order->kind, touching_rule_points(order->kind)));
  }

  /// The entries of two touching panels by a Sauter–Schwab rule: with χ_j, χ_k the affine maps
  /// of the reordered panels (Jacobians 2|T_j|, 2|T_k|), both with the shared corner first
  /// (so χ_j(0) = χ_k(0)), and z_q = χ_j(x̂_q) − χ_k(ŷ_q), ρ_q = |z_q|, δ_q = z_q·n_k at the
  /// rule's nodes (its m leading variables at 1), the direction of x − y integrated exactly
  /// (M_V, M_K of bem/quadrature/radial_moments.hpp for the rule's m):
  ///   V = 4|T_j||T_k| Σ_q w_q M_V(κρ_q)/(4πρ_q),  K[j, k] = 4|T_j||T_k| Σ_q w_q δ_q M_K(κρ_q)/(4πρ_q³);
  /// K[k, j] is the same sum with δ'_q = −z_q·n_j (the roles of the points swapped). K vanishes
  /// for coincident and for coplanar panels (δ ≡ δ' ≡ 0, kCoplanarTouchingTolerance) and is
  /// set to exactly 0 there; the loop then sums V alone.
  TouchingPairEntries touching_pair(const Panel& test, const Panel& trial,
                                    const TouchingOrder& order, const SauterSchwabRule& rule) const {
    const auto corner = [](const Panel& p, const std::array<int, 3>& o, int i) -> const Eigen::Vector3d& {
      return p.corners[size_t(o[size_t(i)])];
    };
    BEMSHAPE_ASSERT(corner(test, order.test, 0) == corner(trial, order.trial, 0),
                    "touching_pair: the panels' first corners differ");
    const Eigen::Vector3d t1 = corner(test, order.test, 1) - corner(test, order.test, 0);
    const Eigen::Vector3d t2 = corner(test, order.test, 2) - corner(test, order.test, 1);
    const Eigen::Vector3d s1 = corner(trial, order.trial, 1) - corner(trial, order.trial, 0);
    const Eigen::Vector3d s2 = corner(trial, order.trial, 2) - corner(trial, order.trial, 1);
    const Eigen::Vector3d& n = trial.normal;
    const Eigen::Vector3d& m = test.normal;
    const double t1n = t1.dot(n), t2n = t2.dot(n);
    const double s1m = s1.dot(m), s2m = s2.dot(m);
    // Coplanar panels (each one's edges orthogonal to the other's normal, to rounding): δ ≡ 0
    // and δ' ≡ 0, both double layers vanish, and only V is summed.
    const double flat = kCoplanarTouchingTolerance *
                        std::max({t1.norm(), t2.norm(), s1.norm(), s2.norm()});
    const bool coplanar = std::max({std::abs(t1n), std::abs(t2n), std::abs(s1m), std::abs(s2m)}) <= flat;
    // A coincident pair is coplanar; its rule may have no double-layer moment (m = 3).
    const bool single_only = coplanar || order.kind == TouchingKind::coincident;
    const int closed = rule.closed_form_variables;
    const LaplaceRadialMoments laplace = laplace_radial_moments(closed);
    // Evaluated in chunks as Eigen arrays, which vectorise the square roots and exponentials.
    constexpr Eigen::Index chunk = 256;
    using Chunk = Eigen::Array<double, Eigen::Dynamic, 1, 0, chunk, 1>;
    using Nodes = Eigen::Map<const Eigen::ArrayXd>;
    const auto size = static_cast<Eigen::Index>(rule.size());
    double sl = 0.0, dl = 0.0, dl_transposed = 0.0;
    Chunk single, double_layer;
    for (Eigen::Index begin = 0; begin < size; begin += chunk) {
      const Eigen::Index count = std::min(chunk, size - begin);
      const Nodes x1(rule.x1.data() + begin, count), x2(rule.x2.data() + begin, count);
      const Nodes y1(rule.y1.data() + begin, count), y2(rule.y2.data() + begin, count);
      const Nodes w(rule.weight.data() + begin, count);
      const Chunk zx = x1 * t1.x() + x2 * t2.x() - y1 * s1.x() - y2 * s2.x();
      const Chunk zy = x1 * t1.y() + x2 * t2.y() - y1 * s1.y() - y2 * s2.y();
      const Chunk zz = x1 * t1.z() + x2 * t2.z() - y1 * s1.z() - y2 * s2.z();
      const Chunk rho2 = zx.square() + zy.square() + zz.square();
      const Chunk inv_rho = rho2.rsqrt();
      if (single_only) {
        if constexpr (Kernel::has_exponential_decay)
          yukawa_radial_moments(closed, Chunk(kernel_.kappa() * rho2 * inv_rho), single,
                                static_cast<Chunk*>(nullptr));
        else
          single = Chunk::Constant(count, laplace.single);
        sl += (w * single * inv_rho).sum();
        continue;
      }
      if constexpr (Kernel::has_exponential_decay) {
        yukawa_radial_moments(closed, Chunk(kernel_.kappa() * rho2 * inv_rho), single,
                              &double_layer);
        single *= inv_rho;
        double_layer *= inv_rho.cube();
      } else {
        single = laplace.single * inv_rho;
        double_layer = laplace.double_layer * inv_rho.cube();
      }
      // z·n_k: the trial panel's own edges are orthogonal to n_k; −z·n_j likewise.
      const Chunk d = x1 * t1n + x2 * t2n;
      const Chunk d_transposed = y1 * s1m + y2 * s2m;
      const Chunk wd = w * double_layer;
      sl += (w * single).sum();
      dl += (wd * d).sum();
      dl_transposed += (wd * d_transposed).sum();
    }
    const double scale = 4.0 * test.area * trial.area * Kernel::inv_four_pi;
    if (single_only) return {scale * sl, 0.0, 0.0};
    return {scale * sl, scale * dl, scale * dl_transposed};
  }

  /// touching_pair for (test, trial) in this orientation, as an entry: the tests of the rules
  /// call it with every n.
  Entry touching_entry(const Panel& test, const Panel& trial, const TouchingOrder& order,
                       const SauterSchwabRule& rule) const {
    const TouchingPairEntries e = touching_pair(test, trial, order, rule);
    return {e.single_layer, e.double_layer};
  }

  /// Computes every touching pair's entries once, both orientations from one rule pass, and
  /// keeps them (24 bytes per ordered pair, about 13 pairs per panel): `entry` then looks
  /// them up. Halves the Sauter–Schwab work of an assembly that needs both (j, k) and (k, j),
  /// which every assembly does. Pairs are found by equal corners, as touching_order does.
  void tabulate_touching_pairs() {
    const auto& panels = *panels_;
    const auto n = static_cast<std::int32_t>(panels.size());
    // Panels around each corner position: sort the 3n corners by coordinates.
    std::vector<std::pair<std::array<double, 3>, std::int32_t>> corners;
    corners.reserve(3 * panels.size());
    for (std::int32_t p = 0; p < n; ++p)
      for (const auto& c : panels[size_t(p)].corners) corners.push_back({{c.x(), c.y(), c.z()}, p});
    std::sort(corners.begin(), corners.end());
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    for (size_t begin = 0; begin < corners.size();) {
      size_t end = begin;
      while (end < corners.size() && corners[end].first == corners[begin].first) ++end;
      for (size_t i = begin; i < end; ++i)
        for (size_t j = begin; j < end; ++j) pairs.emplace_back(corners[i].second, corners[j].second);
      begin = end;
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    touching_offsets_.assign(size_t(n) + 1, 0);
    for (const auto& pair : pairs) ++touching_offsets_[size_t(pair.first) + 1];
    for (size_t p = 0; p < size_t(n); ++p) touching_offsets_[p + 1] += touching_offsets_[p];
    touching_columns_.resize(pairs.size());
    for (size_t s = 0; s < pairs.size(); ++s) touching_columns_[s] = pairs[s].second;
    std::vector<Entry> entries(pairs.size());
    // Each ordered pair's slot is written once, by the pass of the pair's canonical first panel.
#pragma omp parallel for schedule(dynamic, 64)
    for (std::int32_t j = 0; j < n; ++j) {
      if (cancellation_requested()) continue;
      const Panel& test = panels[size_t(j)];
      for (auto s = touching_offsets_[size_t(j)]; s < touching_offsets_[size_t(j) + 1]; ++s) {
        const std::int32_t k = touching_columns_[size_t(s)];
        const Panel& trial = panels[size_t(k)];
        if (face(k) < face(j)) continue;
        const TouchingPairEntries e = touching_pair(test, trial);
        entries[size_t(s)] = {e.single_layer, e.double_layer};
        for (auto t = touching_offsets_[size_t(k)]; t < touching_offsets_[size_t(k) + 1]; ++t)
          if (touching_columns_[size_t(t)] == j) entries[size_t(t)] = {e.single_layer, e.double_layer_transposed};
      }
    }
    throw_if_cancelled();
    touching_entries_ = std::move(entries);
  }

  /// A Yukawa entry whose attenuation allows a low-order rule: centroid of the test panel
  /// times the trial panel's Gauss integral (the outer rule's error is attenuated alike).
  Entry attenuated_entry(const Panel& test, const Panel& trial, const TriangleRule& rule) const {
    const PanelIntegrals p = gauss_panel_integrals(kernel_, trial, test.centroid, rule, false);
    return {test.area * p.single_layer, test.area * p.double_layer};
  }

  /// V and K of test panels row_begin … row_end − 1 and trial panels col_begin … col_end − 1:
  /// single_layer(r, c) = V[row_begin + r, col_begin + c], double_layer(r, c) likewise (both
  /// pre-sized). The entries of `entry`; for Laplace the far-field pairs are computed
  /// kFarFieldLanes at a time (bem/operators/far_field_lanes.hpp), along the row when the range has
  /// one row and along each column otherwise.
  void fill_range(Eigen::Index row_begin, Eigen::Index row_end, Eigen::Index col_begin,
                  Eigen::Index col_end, Eigen::Ref<Eigen::MatrixXd> single_layer,
                  Eigen::Ref<Eigen::MatrixXd> double_layer) const {
    const Eigen::Index m = row_end - row_begin, n = col_end - col_begin;
    const auto one = [&](Eigen::Index r, Eigen::Index c) {
      const Entry e = entry(row_begin + r, col_begin + c);
      single_layer(r, c) = e.single_layer;
      double_layer(r, c) = e.double_layer;
    };
    if constexpr (!Kernel::has_exponential_decay) {
      constexpr Eigen::Index lanes = kFarFieldLanes;
      constexpr double far_ratio = OuterRuleThresholds::far_ratio;
      FarFieldEntries e;
      // Lane l of a pass starting at (r, c) is entry (r + l·dr, c + l·dc): the lanes' values
      // where they were computed, entry() for the rest.
      const auto store = [&](unsigned done, Eigen::Index r, Eigen::Index c, Eigen::Index dr,
                             Eigen::Index dc) {
        for (Eigen::Index l = 0; l < lanes; ++l) {
          if (done & (1u << l)) {
            single_layer(r + l * dr, c + l * dc) = e.single_layer(l);
            double_layer(r + l * dr, c + l * dc) = e.double_layer(l);
          } else {
            one(r + l * dr, c + l * dc);
          }
        }
      };
      if (m == 1) {
        const PanelLanes test = PanelLanes::repeated(arrays_, row_begin);
        Eigen::Index c = 0;
        for (; c + lanes <= n; c += lanes)
          store(laplace_far_field_lanes(test, PanelLanes::consecutive(arrays_, col_begin + c),
                                        far_ratio, e, laplace_rules_),
                0, c, 0, 1);
        for (; c < n; ++c) one(0, c);
        return;
      }
      for (Eigen::Index c = 0; c < n; ++c) {
        const PanelLanes trial = PanelLanes::repeated(arrays_, col_begin + c);
        Eigen::Index r = 0;
        for (; r + lanes <= m; r += lanes)
          store(laplace_far_field_lanes(PanelLanes::consecutive(arrays_, row_begin + r), trial,
                                        far_ratio, e, laplace_rules_),
                r, c, 1, 0);
        for (; r < m; ++r) one(r, c);
      }
      return;
    }
    for (Eigen::Index c = 0; c < n; ++c)
      for (Eigen::Index r = 0; r < m; ++r) one(r, c);
  }

  Eigen::Index size() const { return static_cast<Eigen::Index>(panels_->size()); }
  const Kernel& kernel() const { return kernel_; }

 private:
  Eigen::Index face(Eigen::Index i) const { return faces_ ? (*faces_)[size_t(i)] : i; }

  Kernel kernel_;
  double yukawa_accuracy_ = YukawaAttenuation::absolute_accuracy;
  std::span<const FarFieldRule> laplace_rules_ = far_field_rules();
  const std::vector<Panel>* panels_;
  const std::vector<Eigen::Index>* faces_;  ///< face number of each panel, or null: i
  PanelArrays arrays_;  ///< *panels_ as arrays, for fill_range and fill_row
  // The touching pairs' entries (tabulate_touching_pairs; empty until then), by test panel:
  // trial panels touching_columns_[s] and entries touching_entries_[s] for s in
  // [touching_offsets_[j], touching_offsets_[j + 1]).
  std::vector<std::int64_t> touching_offsets_;
  std::vector<std::int32_t> touching_columns_;
  std::vector<Entry> touching_entries_;
};

}  // namespace bemshape::bem
