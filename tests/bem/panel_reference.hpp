#pragma once
// Brute-force reference values of the panel integrals (bem/quadrature/panel_integral_values.hpp) by
// adaptive subdivision (adaptive_triangle_reference.hpp), with the kernels written out here
// independently of bem/: G = e^{−κr}/(4πr) (κ = 0: Laplace), ∂G/∂n_y = G'(r)(y − x)·n/r, and
// the x-gradients of both.

#include <vector>

#include <Eigen/Core>

#include "bem/quadrature/panel.hpp"

namespace bemshape::testing {

struct ReferenceIntegrals {
  double single_layer = 0, double_layer = 0;
  Eigen::Vector3d single_layer_gradient = Eigen::Vector3d::Zero();
  Eigen::Vector3d double_layer_gradient = Eigen::Vector3d::Zero();
};

/// Natural magnitudes of the entries of a panel for kernel κ (0: Laplace) near the panel, used
/// as absolute floors for entries that are tiny by cancellation or exponential decay:
/// h_eff = min(diameter, 1/κ); single layer area/(4π h_eff), double layer and single-layer
/// gradient area/(4π h_eff²), double-layer gradient area/(4π h_eff³).
struct NearFieldMagnitudes {
  double single_layer, double_layer, single_layer_gradient, double_layer_gradient;
};
NearFieldMagnitudes near_field_magnitudes(const bem::Panel& panel, double kappa);

/// Reference integrals for the panel and target x, each to relative accuracy rel_tol or
/// absolute accuracy rel_tol·1e−4·(its near-field magnitude), whichever is looser.
ReferenceIntegrals reference_panel_integrals(double kappa, const bem::Panel& panel,
                                             const Eigen::Vector3d& x, bool with_gradients,
                                             double rel_tol = 1e-12);

/// The three panel shapes the rule tables are calibrated and checked on: equilateral, right
/// and obtuse, each with a longest edge of 1.
std::vector<bem::Panel> rule_test_panels();

/// `count` unit directions around a panel: the normal, an in-plane direction and a grazing
/// one first, then normal variates from std::mt19937 seeded with `seed`, normalised.
std::vector<Eigen::Vector3d> target_directions(int count, unsigned seed);

}  // namespace bemshape::testing
