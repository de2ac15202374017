#pragma once
// The radial integrals of the Sauter–Schwab rules (bem/quadrature/sauter_schwab_rules.hpp) in closed
// form. Every sub-domain map of those rules is linear in its radial variable ξ ∈ [0, 1]:
// x − y = ξ z, d = (x − y)·n = ξ δ, Jacobian ξ³ J. For the kernels G(r) = E(r)/(4πr) and
// −d G'(r)/r = d E(r)(1 + κr)/(4πr³), with E = 1 (Laplace, κ = 0) or e^{−κr} (Yukawa) and
// ρ = |z|, c = κρ, the ξ-integrals are
//
//   ∫_0^1 ξ³ G(ξρ) dξ          = M_V(c) / (4πρ),   M_V(c) = ∫_0^1 ξ² e^{−cξ} dξ
//                                                         = (2 − e^{−c}(c² + 2c + 2)) / c³,
//   ∫_0^1 ξ³ (−ξδ G'(ξρ)/(ξρ)) dξ = δ M_K(c) / (4πρ³), M_K(c) = ∫_0^1 ξ (1 + cξ) e^{−cξ} dξ
//                                                         = (3 − e^{−c}(c² + 3c + 3)) / c²,
//
// with M_V(0) = 1/3 and M_K(0) = 1/2 (Laplace). So the rules need Gauss points in the three
// angular variables only, and the radial direction is exact for every κ.
//
// Below c = 1 the closed forms lose digits to cancellation (2 − 2 + O(c³)); there the Taylor
// series M_V = Σ_k (−c)^k / (k!(k + 3)) and M_K = Σ_k (−c)^k (1 − k) / (k!(k + 2)) are
// summed instead, 20 terms (the first omitted one is below 1/20! ≈ 4e−19).

#include <array>

#include "linalg/vector_exponential.hpp"

namespace bemshape::bem {

namespace detail {
inline constexpr int kRadialSeriesTerms = 20;
/// Taylor coefficients of M_V and M_K in powers of (−c).
struct RadialSeries {
  std::array<double, kRadialSeriesTerms> single{}, double_layer{};
};
inline constexpr RadialSeries radial_series = [] {
  RadialSeries s;
  double factorial = 1.0;
  for (int k = 0; k < kRadialSeriesTerms; ++k) {
    if (k > 0) factorial *= k;
    s.single[size_t(k)] = 1.0 / (factorial * (k + 3));
    s.double_layer[size_t(k)] = (1.0 - k) / (factorial * (k + 2));
  }
  return s;
}();
}  // namespace detail

/// Below this c = κρ the series replaces the closed forms.
inline constexpr double kRadialSeriesBelow = 1.0;

namespace detail {
/// M_V(c) into `single` and, unless `double_layer` is null, M_K(c) into it: one exponential
/// for both.
template <class Array>
void radial_moments(const Array& c, Array& single, Array* double_layer) {
  const Array e = linalg::vector_exp<Array>(-c);
  const Array c2 = c.square();
  single = (2.0 - e * (c2 + 2.0 * c + 2.0)) / (c2 * c);
  if (double_layer) *double_layer = (3.0 - e * (c2 + 3.0 * c + 3.0)) / c2;
  const auto small = c < kRadialSeriesBelow;
  if (!small.any()) return;
  const auto& s = radial_series;
  constexpr int last = kRadialSeriesTerms - 1;
  Array series_single = Array::Constant(c.size(), s.single[last]);
  for (int k = last - 1; k >= 0; --k) series_single = series_single * (-c) + s.single[size_t(k)];
  single = small.select(series_single, single);
  if (!double_layer) return;
  Array series_double = Array::Constant(c.size(), s.double_layer[last]);
  for (int k = last - 1; k >= 0; --k) series_double = series_double * (-c) + s.double_layer[size_t(k)];
  *double_layer = small.select(series_double, *double_layer);
}
}  // namespace detail

/// M_V(c) and M_K(c) (dimensionless) for every entry of the Eigen array c = κρ > 0.
template <class Array>
void yukawa_radial_moments(const Array& c, Array& single, Array& double_layer) {
  detail::radial_moments(c, single, &double_layer);
}

/// M_V(c) alone, as yukawa_radial_moments gives it: for the pairs whose double layer vanishes
/// (coplanar touching panels).
template <class Array>
void yukawa_radial_single_moment(const Array& c, Array& single) {
  detail::radial_moments(c, single, static_cast<Array*>(nullptr));
}

}  // namespace bemshape::bem
