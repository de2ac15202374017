#pragma once
// The Laplace panel integrals of the treecode's near field (bem/evaluate/laplace_treecode.hpp)
// at the treecode's own accuracy rather than at the 1e−8 of integrate_panel
// (bem/quadrature/panel_integrals.hpp): single and double layer of a flat panel with unit
// density and their gradients ∇_x, G0(r) = 1/(4πr),
//
//   V(x) = ∫_T G0(x − y) dA_y,   K(x) = ∫_T ∂G0/∂n_y dA_y,   ∇V, ∇K,
//
// each within kNearPanelAccuracy of its natural magnitude at the target's distance r from the
// centroid (|T|·|G0^{(k)}(r)| for the k-th derivative). A treecode with θ = 0.5 and p = 10 is
// itself within about 4e−5 of the direct sums (docs/benchmarks.md, "Interior evaluation at
// many points"), so 1e−8 per panel buys nothing; the panels it integrates lie within a few
// diameters of the target, where the 1e−8 rules need 36–64 points.
//
// Rule selection by η = |x − centroid| / diameter: the cheapest Gauss rule on the triangle
// (bem/quadrature/triangle_quadrature.hpp) of near_panel_rules() whose η range contains the
// target, the closed forms of bem/quadrature/laplace_triangle_potentials.hpp below the last
// row. Those take 75–85 ns with gradients at any distance (2-core Zen 3), where the rules
// they replace took 140 ns (12 points, η 2.5–4) to 720 ns (64 points, η 1–1.5) and the polar
// scheme 3.5 μs at η 0.5.

#include <array>

#include <Eigen/Core>

#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integral_values.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/quadrature/laplace_triangle_potentials.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"

namespace bemshape::bem {

/// The accuracy of near_panel_integrals, relative to the natural magnitude of each entry.
inline constexpr double kNearPanelAccuracy = 1e-6;

/// One row of the table: the rule keeps all four entries within kNearPanelAccuracy for
/// every target with η ≥ min_ratio.
struct NearPanelRule {
  double min_ratio;
  const TriangleRule* rule;
};

/// The table, cheapest rule first. Measured worst errors over an equilateral, a right and an
/// obtuse panel and 43 directions per ratio (tests/bem/evaluate/test_near_panel_integrals.cpp
/// prints them; docs/quadrature.md, "The treecode's near field"), each row at the smallest
/// ratio it serves: 3 points from η 40 (2.5e−7), 7 from 4 (5.5e−7). Nearer targets take the
/// closed forms, exact to rounding (about 1e−12 of the entries' magnitudes).
inline const std::array<NearPanelRule, 2>& near_panel_rules() {
  static const std::array<NearPanelRule, 2> table = {{
      {40.0, &symmetric_triangle_rule(2)},
      {4.0, &symmetric_triangle_rule(5)},
  }};
  return table;
}

/// V, K and, if with_gradients, ∇V and ∇K of `panel` at x within kNearPanelAccuracy.
inline PanelIntegrals near_panel_integrals(const Panel& panel, const Eigen::Vector3d& x,
                                           bool with_gradients) {
  const double ratio2 = (x - panel.centroid).squaredNorm() / (panel.diameter * panel.diameter);
  for (const NearPanelRule& row : near_panel_rules())
    if (ratio2 >= row.min_ratio * row.min_ratio)
      return gauss_panel_integrals(LaplaceKernel{}, panel, x, *row.rule, with_gradients);
  return laplace_triangle_potentials(panel, x, with_gradients);
}

}  // namespace bemshape::bem
