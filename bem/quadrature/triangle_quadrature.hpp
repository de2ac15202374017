#pragma once
// Quadrature rules on the reference triangle T̂ = {(ξ, η): ξ, η ≥ 0, ξ + η ≤ 1}, weights
// normalised to sum 1, so that for a flat triangle T with corners a, b, c
//
//   ∫_T f dA ≈ |T| Σ_q w_q f(a + ξ_q (b − a) + η_q (c − a)).
//
// Two families:
//  * symmetric Gauss rules (invariant under the permutations of the barycentric coordinates,
//    all weights positive, all points inside) of degree 1, 2, 4, 5, 6 and 8 with 1, 3, 6, 7,
//    12 and 16 points. Their nodes and weights are the published values of D. A. Dunavant,
//    "High degree efficient symmetrical Gaussian quadrature rules for the triangle",
//    Int. J. Numer. Meth. Eng. 21 (1985) 1129–1148; tests/bem/quadrature/test_triangle_quadrature.cpp
//    checks that each rule integrates every monomial ξ^i η^j, i + j ≤ degree, to rounding.
//  * collapsed (Duffy) Gauss rules of any order n: ξ = u, η = (1 − u) v with n-point
//    Gauss–Legendre rules in u and v, n² points, exact to degree 2n − 2. Used for the
//    degrees above 8 and, being built from Gauss–Legendre alone, by the test reference.

#include <vector>

namespace bemshape::bem {

struct TriangleRule {
  int degree = 0;              ///< exact for polynomials of total degree ≤ degree
  std::vector<double> xi;      ///< ξ_q
  std::vector<double> eta;     ///< η_q
  std::vector<double> weight;  ///< w_q, Σ w_q = 1
  int size() const { return static_cast<int>(weight.size()); }
};

/// Degrees available as symmetric rules, ascending.
inline constexpr int symmetric_triangle_degrees[] = {1, 2, 4, 5, 6, 8};

/// The cached symmetric rule of the smallest tabulated degree ≥ `degree` (1 ≤ degree ≤ 8;
/// InternalError otherwise).
const TriangleRule& symmetric_triangle_rule(int degree);

/// The cached collapsed Gauss rule with n × n points (1 ≤ n ≤ 32), exact to degree 2n − 2.
const TriangleRule& collapsed_gauss_rule(int n);

}  // namespace bemshape::bem
