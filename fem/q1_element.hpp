#pragma once
// Bilinear (2-D) and trilinear (3-D) Q1 elements on a square/cubic cell of side h.
//
// A cell's 2^D nodes are numbered by their corner q ∈ {0,1}^D (q_d = 1: upper side along
// axis d). The shape functions are tensor products φ_q(x) = Π_d ℓ_{q_d}(x_d) of the 1-D hat
// functions, so every element integral factorises into 1-D integrals over [0, h]:
//   ∫ ℓ_a ℓ_b   = h/6·(2 if a = b, 1 otherwise)        (1-D mass m)
//   ∫ ℓ_a' ℓ_b' = 1/h·(1 if a = b, −1 otherwise)       (1-D stiffness k)
//   ∫ ℓ_a'      = +1 if a = 1, −1 if a = 0;  ∫ ℓ_a = h/2.
// The element matrices depend on a node pair only through its offset o = q_b − q_a ∈
// {−1, 0, 1}^D, which the functions below take:
//   M_e(o) = Π_d m(o_d)                                    (∫ φ_a φ_b)
//   K_e(o) = Σ_d k(o_d)·Π_{e≠d} m(o_e)                     (∫ ∇φ_a·∇φ_b)
//   G_e(q, i) = ∫ ∂φ_q/∂x_i = ±(h/2)^{D−1}, + iff q_i = 1  (source term of the PDE)

#include <array>
#include <cmath>

namespace bemshape::fem {

/// 1-D mass entry for an offset o ∈ {−1, 0, 1} on a cell of length h.
constexpr double q1_mass_1d(int offset, double h) {
  return offset == 0 ? h / 3.0 : h / 6.0;
}
/// 1-D stiffness entry for an offset o ∈ {−1, 0, 1} on a cell of length h.
constexpr double q1_stiffness_1d(int offset, double h) {
  return offset == 0 ? 1.0 / h : -1.0 / h;
}

/// ∫_cell φ_a φ_b for two nodes of one cell with offset o [model units^D].
template <int D>
double q1_mass(const std::array<int, D>& offset, double h) {
  double value = 1.0;
  for (int d = 0; d < D; ++d)
    value *= q1_mass_1d(offset[d], h);
  return value;
}

/// ∫_cell ∇φ_a·∇φ_b for two nodes of one cell with offset o [model units^(D−2)].
template <int D>
double q1_stiffness(const std::array<int, D>& offset, double h) {
  double value = 0.0;
  for (int d = 0; d < D; ++d) {
    double term = q1_stiffness_1d(offset[d], h);
    for (int e = 0; e < D; ++e)
      if (e != d)
        term *= q1_mass_1d(offset[e], h);
    value += term;
  }
  return value;
}

/// ∫_cell ∂φ_q/∂x_i for the node at corner q of the cell [model units^(D−1)].
template <int D>
double q1_gradient_integral(const std::array<int, D>& corner, int i, double h) {
  const double magnitude = std::pow(0.5 * h, D - 1);
  return corner[i] == 1 ? magnitude : -magnitude;
}

/// Gradient of a Q1 function at the cell centre: ∂u/∂x_i = (1/h)·2^{1−D}·Σ_q ±u_q, + iff
/// q_i = 1 (the centre value of ∂φ_q/∂x_i). Cell-centre gradients are superconvergent on
/// uniform grids, which is why features are evaluated there.
template <int D>
double q1_centre_gradient_weight(const std::array<int, D>& corner, int i, double h) {
  const double magnitude = 1.0 / (h * static_cast<double>(1 << (D - 1)));
  return corner[i] == 1 ? magnitude : -magnitude;
}

/// Corner q ∈ {0,1}^D of the bit pattern `bits` (bit d = q_d).
template <int D>
constexpr std::array<int, D> corner_of(int bits) {
  std::array<int, D> q{};
  for (int d = 0; d < D; ++d)
    q[d] = (bits >> d) & 1;
  return q;
}

}  // namespace bemshape::fem
