#pragma once
// Near-field and singular panel integrals by polar coordinates in the panel's plane
// (docs/quadrature.md derives every formula below).
//
// Let x be the target, d = (x − a)·n its signed height above the plane of the panel T, x' its
// projection, ρ the in-plane distance from x', ρ' = √(ρ² + d²) = |x − y|. T is the signed sum
// of the three triangles (x', P_i, P_{i+1}) over its edges; with polar angle θ around x' and
// R(θ) the distance from x' to the edge along θ,
//
//   ∫_T f(|x − y|) dA = Σ_edges ∫ dθ ∫_0^{R(θ)} f(√(ρ² + d²)) ρ dρ      (θ signed).
//
// The radial integrals of the value kernels are exact (per unit density, times 1/4π):
//   single layer Laplace   ρ' − |d|
//   single layer Yukawa    (e^{−κ|d|} − e^{−κρ'})/κ
//   double layer Laplace   sign(d) − d/ρ'
//   double layer Yukawa    sign(d)e^{−κ|d|} − d e^{−κρ'}/ρ'
// (with ∂G/∂n_y = G'(r)(y − x)·n/r = −d G'(r)/r, so the double layer is positive above the
// panel). Along each edge the angle is parametrised by t = p sinh v, p the distance from x' to
// the edge's line and t the abscissa from the foot of the perpendicular, dθ = dv / cosh v;
// composite Gauss–Legendre in v on pieces graded from the point of the edge nearest to x
// resolves both the near-singular geometry (p → 0) and the e^{−κρ'} boundary layer.
//
// Gradients: n·∇ single layer = −double layer; the normal part of ∇ double layer and the
// Laplace in-plane parts are closed forms; the Yukawa in-plane parts use the radial tails
// ∫_R^∞ in the variable ρ = |d| sinh u, Gauss–Legendre in u.
//
// Targets in the plane (|d| ≤ 1e−12·diameter, treated as d = 0, so that collocation points
// computed on the panel get the principal value whatever the rounding): values are exact limits (the double layer is 0, the principal
// value on the panel). Gradients for d = 0 and x' inside T are the average of the two one-sided
// limits: the single-layer normal derivative is 0 there; the in-plane parts are the common
// limit. Targets on an edge line with d = 0 are singular and not supported (the result is finite
// but meaningless).

#include <Eigen/Core>

#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integral_values.hpp"

namespace bemshape::bem {

/// How finely the polar scheme resolves the angle: Gauss–Legendre points per composite
/// piece, and the decay e^{−κδ} (δ = ρ' − c, c the distance from x to T) beyond which the
/// Yukawa pieces of an edge are dropped. The default is the full accuracy, about 1e−10 of
/// the value or better; coarser ones serve targets whose whole contribution is attenuated
/// far below the accuracy the caller needs (for_accuracy).
struct PolarResolution {
  int points_per_piece = 10;
  double negligible_exponent = 45.0;
  /// The coarsest resolution whose angular integrals stay within `relative_accuracy` of
  /// the magnitude of the value (the bound e^{−κc}|T|/(4πc) for the Yukawa single layer):
  /// measured in tests/bem/quadrature/test_polar_quadrature.cpp ("polar resolution"). At
  /// 1e−10 or below, the default.
  static PolarResolution for_accuracy(double relative_accuracy);
};

/// Panel integrals by the polar scheme, valid for every target (used for targets near or on
/// the panel: ~40–300 kernel evaluations, eight at a time, more for gradients;
/// docs/quadrature.md, "Throughput"). `resolution` applies to the values; gradients are always
/// at full accuracy.
/// Kernel ∈ {LaplaceKernel, YukawaKernel} (explicitly instantiated).
template <class Kernel>
PanelIntegrals polar_panel_integrals(const Kernel& kernel, const Panel& panel,
                                     const Eigen::Vector3d& x, bool with_gradients,
                                     const PolarResolution& resolution = {});

}  // namespace bemshape::bem
