#pragma once
// The free-space Green's function of the modified Helmholtz (Yukawa) operator in 3-D,
//
//   Gκ(r) = e^{−κr} / (4π r),   r = |x − y| > 0,  κ > 0  [1 / model units],
//
// with (−Δ_x + κ²) Gκ = δ(x − y). bemshape uses it outside the solid, where the shape-feature
// field solves Δs = κ²s with κ = 2/(a·h0) (a = 0.2 by default, h0 the characteristic length;
// docs/theory.md). Same interface as LaplaceKernel, so every quadrature is written once.

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Core>

#include "bem/kernels/radial_values.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {

struct YukawaKernel {
  static constexpr bool has_exponential_decay = true;
  static constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;
  /// Beyond κ·r = 40 the kernel is below e^{−40} ≈ 4e−18 of its value at r ~ 1/κ: the panel
  /// integrals return an exact 0 there (bem/quadrature/panel_integrals.hpp), far below the 1e−8 accuracy
  /// the solver needs and below double rounding of any near-field entry.
  static constexpr double negligible_exponent = 40.0;

  /// Throws InputError unless κ is positive and finite.
  explicit YukawaKernel(double kappa) : kappa_(kappa) {
    if (!(kappa > 0.0) || !std::isfinite(kappa))
      throw InputError("Yukawa kernel: kappa = " + std::to_string(kappa) +
                       " must be a positive finite number [1/model units]; kappa = 2/(a*h0)");
  }

  double kappa() const noexcept { return kappa_; }
  /// Distance beyond which Gκ and its derivatives count as exactly zero [model units].
  double cutoff_distance() const noexcept { return negligible_exponent / kappa_; }

  /// Gκ(r) = e^{−κr}/(4πr).
  double value(double r) const noexcept { return inv_four_pi * std::exp(-kappa_ * r) / r; }
  /// Gκ'(r) = −e^{−κr}(1 + κr)/(4πr²).
  double radial_derivative(double r) const noexcept {
    return -inv_four_pi * std::exp(-kappa_ * r) * (1.0 + kappa_ * r) / (r * r);
  }
  /// Gκ(r) and Gκ'(r) from one exponential.
  RadialValues values(double r) const noexcept {
    const double g = inv_four_pi * std::exp(-kappa_ * r) / r;
    return {g, -g * (1.0 + kappa_ * r) / r};
  }
  /// Gκ''(r) = e^{−κr}(κ²r² + 2κr + 2)/(4πr³).
  double second_radial_derivative(double r) const noexcept {
    const double kr = kappa_ * r;
    return inv_four_pi * std::exp(-kr) * (kr * kr + 2.0 * kr + 2.0) / (r * r * r);
  }
  /// ∇_x Gκ(|x − y|) = Gκ'(r)(x − y)/r.
  Eigen::Vector3d gradient(const Eigen::Vector3d& x, const Eigen::Vector3d& y) const {
    const Eigen::Vector3d diff = x - y;
    const double r = diff.norm();
    return (radial_derivative(r) / r) * diff;
  }

 private:
  double kappa_;
};

}  // namespace bemshape::bem
