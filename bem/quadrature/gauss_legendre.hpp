#pragma once
// n-point Gauss–Legendre rules on [−1, 1]: ∫_{−1}^{1} f(t) dt ≈ Σ_i w_i f(t_i), exact for
// polynomials of degree ≤ 2n − 1. Nodes are the roots of the Legendre polynomial P_n, found by
// Newton's method on the three-term recurrence (n P_n = (2n−1) t P_{n−1} − (n−1) P_{n−2}),
// weights w_i = 2 / ((1 − t_i²) P_n'(t_i)²). Rules up to max_gauss_legendre_points are
// computed once, on first use (thread-safe), and shared.

#include <span>
#include <vector>

namespace bemshape::bem {

/// Largest n served from the cache; more points than this never pay in bemshape (the polar
/// scheme uses composite rules instead).
inline constexpr int max_gauss_legendre_points = 64;

struct GaussLegendreRule {
  std::vector<double> nodes;    ///< t_i ∈ (−1, 1), ascending
  std::vector<double> weights;  ///< w_i > 0, Σ w_i = 2
  int size() const { return static_cast<int>(nodes.size()); }
};

/// The cached n-point rule, 1 ≤ n ≤ max_gauss_legendre_points (InternalError otherwise).
const GaussLegendreRule& gauss_legendre(int n);

/// Computes an n-point rule without the cache (n ≥ 1).
GaussLegendreRule compute_gauss_legendre(int n);

}  // namespace bemshape::bem
