#pragma once
// The integrals of the Sauter–Schwab rules (bem/quadrature/sauter_schwab_rules.hpp) along the
// direction of x − y, in closed form. In every sub-domain map of those rules the difference of
// the two points is a product of leading variables times a vector of the others:
//
//   vertex (m = 1):      x − y = ξ · z(η1, η2, η3),       Jacobian ξ³ · J(η),
//   edge (m = 2):        x − y = ξη1 · z(η2, η3),         Jacobian ξ³η1² · J(η2),
//   coincident (m = 3):  x − y = ξη1η2 · z(η3),           Jacobian ξ³η1²η2,
//
// (the edge and coincident maps are also of the form m = 1 and, coincident, m = 2). With
// u the product of the m leading variables, integrating them out of ξ³η1²η2-type Jacobians
// leaves one integral over u ∈ [0, 1] with the weight
//
//   w_1(u) = u³,   w_2(u) = u²(1 − u),   w_3(u) = u(1 − u)²/2
//
// (the density of the product of variables with densities ξ³, η1², η2 on [0, 1]). For the
// kernels G(r) = E(r)/(4πr) and −d G'(r)/r = d E(r)(1 + κr)/(4πr³), E = 1 (Laplace, κ = 0) or
// e^{−κr} (Yukawa), with ρ = |z|, δ = z·n (d = uδ) and c = κρ:
//
//   ∫_0^1 w_m(u) G(uρ) du          = M_V(c) / (4πρ),    M_V(c) = ∫_0^1 w_m(u) u^{−1} e^{−cu} du,
//   ∫_0^1 w_m(u) (−uδ G'(uρ)/(uρ)) du = δ M_K(c) / (4πρ³), M_K(c) = ∫_0^1 w_m(u) u^{−2} (1 + cu) e^{−cu} du,
//
// in closed form (e = e^{−c}):
//
//   m = 1:  M_V = (2 − e(c² + 2c + 2)) / c³,   M_K = (3 − e(c² + 3c + 3)) / c²   (Laplace 1/3, 1/2),
//   m = 2:  M_V = (c − 2 + e(c + 2)) / c³,     M_K = (2c − 3 + e(c + 3)) / c²    (Laplace 1/6, 1/2),
//   m = 3:  M_V = (c² − 2c + 2 − 2e) / (2c³)                                     (Laplace 1/6).
//
// M_K of m = 3 diverges at u = 0; it is never needed, since the double layer of a flat panel
// with itself vanishes. So a rule needs Gauss points in the 4 − m remaining variables only,
// and the direction of x − y is exact for every κ: the boundary layer of width 1/(κ·diameter)
// that e^{−κr} puts into these variables is integrated exactly, not resolved by points.
//
// Below c = 1 the closed forms lose digits to cancellation (their numerators vanish like c³ or
// c²); there the Taylor series M = Σ_k a_k (−c)^k is summed instead, 20 terms (the first
// omitted one is below 1/20! ≈ 4e−19), with
//
//   m = 1:  a_k^V = 1/(k!(k + 3)),                 a_k^K = (1 − k)/(k!(k + 2)),
//   m = 2:  a_k^V = 1/(k!(k + 2)(k + 3)),          a_k^K = (1 − k)/(k!(k + 1)(k + 2)),
//   m = 3:  a_k^V = 1/(k!(k + 1)(k + 2)(k + 3)).

#include <array>

#include "core/assert.hpp"
#include "linalg/vector_exponential.hpp"

namespace bemshape::bem {

namespace detail {
inline constexpr int kRadialSeriesTerms = 20;
/// Taylor coefficients of M_V and M_K in powers of (−c), for m = 1, 2, 3 (index m − 1).
struct RadialSeries {
  std::array<std::array<double, kRadialSeriesTerms>, 3> single{}, double_layer{};
};
inline constexpr RadialSeries radial_series = [] {
  RadialSeries s;
  double factorial = 1.0;
  for (int k = 0; k < kRadialSeriesTerms; ++k) {
    if (k > 0) factorial *= k;
    s.single[0][size_t(k)] = 1.0 / (factorial * (k + 3));
    s.double_layer[0][size_t(k)] = (1.0 - k) / (factorial * (k + 2));
    s.single[1][size_t(k)] = 1.0 / (factorial * (k + 2) * (k + 3));
    s.double_layer[1][size_t(k)] = (1.0 - k) / (factorial * (k + 1) * (k + 2));
    s.single[2][size_t(k)] = 1.0 / (factorial * (k + 1) * (k + 2) * (k + 3));
  }
  return s;
}();

template <class Array>
Array radial_series_sum(const std::array<double, kRadialSeriesTerms>& a, const Array& c) {
  constexpr int last = kRadialSeriesTerms - 1;
  Array sum = Array::Constant(c.size(), a[last]);
  for (int k = last - 1; k >= 0; --k) sum = sum * (-c) + a[size_t(k)];
  return sum;
}
}  // namespace detail

/// Below this c = κρ the series replaces the closed forms.
inline constexpr double kRadialSeriesBelow = 1.0;

/// The Laplace limits (c = 0) of M_V and M_K for m variables in closed form (M_K of m = 3
/// is not defined and returned as 0).
struct LaplaceRadialMoments {
  double single, double_layer;
};
constexpr LaplaceRadialMoments laplace_radial_moments(int m) {
  return m == 1 ? LaplaceRadialMoments{1.0 / 3.0, 0.5}
         : m == 2 ? LaplaceRadialMoments{1.0 / 6.0, 0.5}
                  : LaplaceRadialMoments{1.0 / 6.0, 0.0};
}

/// M_V(c) into `single` and, unless `double_layer` is null, M_K(c) into it (one exponential
/// for both), for every entry of the Eigen array c = κρ > 0, with m ∈ {1, 2, 3} variables in
/// closed form (m = 3: `double_layer` must be null). Dimensionless.
template <class Array>
void yukawa_radial_moments(int m, const Array& c, Array& single, Array* double_layer) {
  BEMSHAPE_ASSERT(m >= 1 && m <= 3, "yukawa_radial_moments: m outside 1..3");
  BEMSHAPE_ASSERT(m < 3 || double_layer == nullptr,
                  "yukawa_radial_moments: the double-layer moment of m = 3 diverges");
  const Array e = linalg::vector_exp<Array>(-c);
  const Array c2 = c.square();
  if (m == 1) {
    single = (2.0 - e * (c2 + 2.0 * c + 2.0)) / (c2 * c);
    if (double_layer) *double_layer = (3.0 - e * (c2 + 3.0 * c + 3.0)) / c2;
  } else if (m == 2) {
    single = (c - 2.0 + e * (c + 2.0)) / (c2 * c);
    if (double_layer) *double_layer = (2.0 * c - 3.0 + e * (c + 3.0)) / c2;
  } else {
    single = (c2 - 2.0 * c + 2.0 - 2.0 * e) / (2.0 * c2 * c);
  }
  const auto small = c < kRadialSeriesBelow;
  if (!small.any()) return;
  const auto& s = detail::radial_series;
  single = small.select(detail::radial_series_sum(s.single[size_t(m - 1)], c), single);
  if (double_layer)
    *double_layer =
        small.select(detail::radial_series_sum(s.double_layer[size_t(m - 1)], c), *double_layer);
}

}  // namespace bemshape::bem
