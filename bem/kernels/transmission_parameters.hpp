#pragma once
// Coefficients of the transmission problem solved for each coordinate direction i:
//   Δs_i = 0 in Ω (Laplace),   Δs_i − κ² s_i = 0 outside (modified Helmholtz / Yukawa),
//   [s_i] = 0 and ∂_n s_i(inside) − ∂_n s_i(outside) = n_i/ã on Γ,  s_i → 0 at infinity,
// which is Yamada's −div(ã∇s_i − e_iχ) + α(1−χ)s_i = 0 with ã = a·h0², α = 4/a and
// κ = √(α/ã) = 2/(a·h0).

#include <cmath>
#include <string>

#include "core/errors.hpp"

namespace bemshape::bem {

/// The default element size rule: longest edge = kDefaultKappaEdge / κ (= 1.5·a·h0, i.e.
/// 0.3·h0 for a = 0.2). Measured on the ball R = 0.5, h0 = 0.3 (docs/validation.md): at
/// κ·h = 2.7 the interior f_h is within 0.33% and the surface f_h within 0.5% of the closed
/// form; at κ·h = 5.4 the errors are 0.8% and 1.2%. Flat walls tolerate κ·h = 5 (0.03% on a
/// plate); the rule is set for curved ones.
inline constexpr double kDefaultKappaEdge = 3.0;

struct TransmissionParameters {
  double a_tilde = 0.0;  ///< ã = a·h0² [model units²]
  double kappa = 0.0;    ///< κ = 2/(a·h0) [1/model units]

  /// From the characteristic length h0 [model units] and the dimensionless a (default 0.2).
  static TransmissionParameters from_shape(double h0, double a) {
    if (!(std::isfinite(h0) && h0 > 0.0))
      throw InputError("h0 must be a positive length, got " + std::to_string(h0));
    if (!(std::isfinite(a) && a > 0.0))
      throw InputError("a must be a positive number, got " + std::to_string(a));
    return {a * h0 * h0, 2.0 / (a * h0)};
  }

  /// Longest element edge of the default rule [model units].
  double default_max_edge() const { return kDefaultKappaEdge / kappa; }
};

}  // namespace bemshape::bem
