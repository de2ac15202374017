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
};

}  // namespace bemshape::bem
