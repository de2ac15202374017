#pragma once
// The Laplace single- and double-layer potentials of a flat triangle with unit density, and
// their gradients, in closed form (docs/quadrature.md, "Laplace potentials of a triangle in
// closed form"): exact for every target off the panel's edges, at the cost of three
// logarithms, one arctangent and a few square roots, whatever the target's distance.
//
// Let h = (x − a)·n be the target's height above the panel's plane (n the right-hand-rule
// normal), x' its projection, and for each edge i from corner A to corner B: s the edge's
// unit direction, m = s × n its outward normal in the plane, t = (A − x')·m the signed
// distance from x' to the edge's line (> 0 on the panel's side), ξ∓ = (A − x')·s and
// (B − x')·s the abscissae of its ends, R∓ = |x − A| and |x − B|, R0² = t² + h², and
//
//   f_i = ∫_edge dl/r = ln((R+ + ξ+)/(R− + ξ−)),     g_i = ∫_edge dl/r³ = (ξ+/R+ − ξ−/R−)/R0².
//
// With Ω = h ∫_T dA/r³ the signed solid angle (positive above the panel; Van Oosterom and
// Strackee's formula) and G0 = 1/(4πr), ∂G0/∂n_y = h/(4πr³) (bem/quadrature/
// panel_integral_values.hpp):
//
//   4π V  = ∫_T dA/r = Σ_i t_i f_i − h Ω           (polar coordinates about x', radius exact)
//   4π K  = Ω
//   4π ∇V = −Σ_i f_i m_i − Ω n                      (in the plane: the divergence theorem)
//   4π ∇K = −h Σ_i g_i m_i − (Σ_i t_i g_i) n
//
// f and g are evaluated in the forms without cancellation ((R + ξ)(R − ξ) = R0²). Targets
// within 1e−12 of the diameter of the plane are in it (h = 0, as the polar scheme of
// bem/quadrature/polar_quadrature.hpp takes them): K is then its principal value 0 and the
// normal part of ∇V the mean of its one-sided limits, 0. Targets on an edge's line in the
// plane are singular (V's gradient has a logarithm there) and not supported.
//
// Far from the panel the sums cancel: at 100 diameters V keeps about 10 digits, and the
// Gauss rules of bem/quadrature/panel_integrals.hpp are cheaper there anyway; the callers use
// this within a few diameters.

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Core>

#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integral_values.hpp"

namespace bemshape::bem {

/// V, K and, if with_gradients, ∇V and ∇K of `panel` at x for G0 = 1/(4πr), in closed form.
inline PanelIntegrals laplace_triangle_potentials(const Panel& panel, const Eigen::Vector3d& x,
                                                  bool with_gradients) {
  constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;
  const Eigen::Vector3d& n = panel.normal;
  const std::array<Eigen::Vector3d, 3> r = {panel.corners[0] - x, panel.corners[1] - x,
                                            panel.corners[2] - x};
  const std::array<double, 3> length = {r[0].norm(), r[1].norm(), r[2].norm()};
  // h = (x − a)·n, the mean over the corners (equal in exact arithmetic).
  double h = -(r[0] + r[1] + r[2]).dot(n) / 3.0;
  if (std::abs(h) <= 1e-12 * panel.diameter) h = 0.0;

  // Ω = −2 atan2(r0·(r1 × r2), |r0||r1||r2| + (r0·r1)|r2| + (r0·r2)|r1| + (r1·r2)|r0|): the
  // triple product is −2|T|h, so Ω has the sign of h.
  double omega = 0.0;
  if (h != 0.0) {
    const double triple = r[0].dot(r[1].cross(r[2]));
    const double denominator = length[0] * length[1] * length[2] + r[0].dot(r[1]) * length[2] +
                               r[0].dot(r[2]) * length[1] + r[1].dot(r[2]) * length[0];
    omega = -2.0 * std::atan2(triple, denominator);
  }

  double single = -h * omega;
  Eigen::Vector3d grad_single = Eigen::Vector3d::Zero(), grad_double = Eigen::Vector3d::Zero();
  double normal_double = 0.0;
  const double on_line = 1e-12 * panel.diameter;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Eigen::Vector3d& a = r[size_t(i)];  // A − x
    const Eigen::Vector3d& b = r[size_t(j)];  // B − x
    const double edge_length = (b - a).norm();
    const Eigen::Vector3d s = (b - a) / edge_length;
    const Eigen::Vector3d m = s.cross(n);
    // (A − x')·m = (A − x)·m, m being orthogonal to n.
    const double t = a.dot(m);
    const double xi_minus = a.dot(s), xi_plus = b.dot(s);
    const double r_minus = length[size_t(i)], r_plus = length[size_t(j)];
    const double r0_squared = t * t + h * h;
    const bool skip_log = std::abs(t) <= on_line && h == 0.0;  // x on this edge's line
    double f = 0.0;
    if (!skip_log) {
      if (xi_minus >= 0.0)
        f = std::log((r_plus + xi_plus) / (r_minus + xi_minus));
      else if (xi_plus <= 0.0)
        f = std::log((r_minus - xi_minus) / (r_plus - xi_plus));
      else
        f = std::log((r_plus + xi_plus) * (r_minus - xi_minus) / r0_squared);
      single += t * f;
    }
    if (!with_gradients) continue;
    grad_single -= f * m;
    if (skip_log) continue;
    // g = (ξ+/R+ − ξ−/R−)/R0², with ξ/R ∓ 1 = ∓R0²/(R(R ± ξ)) on the edges' sides.
    double g;
    if (xi_minus >= 0.0)
      g = 1.0 / (r_minus * (r_minus + xi_minus)) - 1.0 / (r_plus * (r_plus + xi_plus));
    else if (xi_plus <= 0.0)
      g = 1.0 / (r_plus * (r_plus - xi_plus)) - 1.0 / (r_minus * (r_minus - xi_minus));
    else
      g = (xi_plus / r_plus - xi_minus / r_minus) / r0_squared;
    grad_double -= (h * g) * m;
    normal_double -= t * g;
  }

  PanelIntegrals out;
  out.single_layer = inv_four_pi * single;
  out.double_layer = inv_four_pi * omega;
  if (with_gradients) {
    out.single_layer_gradient = inv_four_pi * (grad_single - omega * n);
    out.double_layer_gradient = inv_four_pi * (grad_double + normal_double * n);
  }
  return out;
}

}  // namespace bemshape::bem
