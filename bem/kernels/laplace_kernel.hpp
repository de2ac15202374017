#pragma once
// The free-space Green's function of the Laplace operator in 3-D,
//
//   G0(r) = 1 / (4π r),   r = |x − y| > 0  [1 / model units],
//
// with −Δ_x G0 = δ(x − y). bemshape uses it inside the solid, where the shape-feature field s
// is harmonic (docs/theory.md). Kernels are small value types: the panel quadrature
// (bem/quadrature/panel_integrals.hpp) and the assembly are written once and instantiated per kernel.
// `has_exponential_decay` selects the closed-form radial integrals with `if constexpr`.

#include <numbers>

#include <Eigen/Core>

#include "bem/kernels/radial_values.hpp"

namespace bemshape::bem {

struct LaplaceKernel {
  /// G0 has no exponential factor: the polar quadrature uses its Laplace closed forms.
  static constexpr bool has_exponential_decay = false;
  static constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;

  /// κ of the modified Helmholtz family; 0 for Laplace.
  constexpr double kappa() const noexcept { return 0.0; }

  /// G0(r) = 1/(4πr).
  double value(double r) const noexcept { return inv_four_pi / r; }
  /// G0'(r) = −1/(4πr²).
  double radial_derivative(double r) const noexcept { return -inv_four_pi / (r * r); }
  /// G0(r) and G0'(r) together (the quadrature loops need both at every point).
  RadialValues values(double r) const noexcept {
    const double g = inv_four_pi / r;
    return {g, -g / r};
  }
  /// G0''(r) = 2/(4πr³).
  double second_radial_derivative(double r) const noexcept {
    return 2.0 * inv_four_pi / (r * r * r);
  }
  /// ∇_x G0(|x − y|) = G0'(r)(x − y)/r = −(x − y)/(4πr³).
  Eigen::Vector3d gradient(const Eigen::Vector3d& x, const Eigen::Vector3d& y) const {
    const Eigen::Vector3d diff = x - y;
    const double r = diff.norm();
    return (radial_derivative(r) / r) * diff;
  }
};

}  // namespace bemshape::bem
