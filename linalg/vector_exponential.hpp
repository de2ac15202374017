#pragma once
// e^x over an Eigen array of doubles, the exponential of the Yukawa kernel's quadrature
// (panel_integrals, radial_moments, polar_quadrature).
//
// Eigen 3.4 evaluates a double exponential as a rational approximation, whose division
// shares the divider with the square roots and divisions of the kernel around it. Here, on
// AVX2 with FMA, four lanes at a time:
//
//   x = k ln 2 + r,   k = round(x / ln 2),   |r| ≤ ln 2 / 2,
//   e^x = 2^k e^r,    e^r = Σ_{n=0}^{12} r^n / n!  (Estrin's scheme, fused multiply-adds),
//
// ln 2 split in two parts (Cody–Waite) so that r is exact to rounding, and 2^k built in the
// exponent bits. The Taylor remainder relative to e^r is at most (ln 2/2)^13/13! · 2 =
// 3.3e−16, so with rounding the result is within 6e−16 relative of e^x for −708 ≤ x ≤ 709
// (tests/linalg/test_vector_exponential.cpp); below −708 it is 0 (the true value, under
// 3.3e−308, is a subnormal), above 709 it is e^709. A NaN stays NaN. On a 2-core Zen 3 an
// entry costs 1.4–1.7 ns against Eigen's 2.2–2.7 ns (`bench_panel_integrals`;
// docs/benchmarks.md, "Vector exp").
//
// Without AVX2 and FMA, and with AVX-512 (where Eigen's exponential runs on eight lanes and
// was measured as is), this is Eigen's own `exp`, which clamps x below at about −709.4: there
// e^x for x < −708 is not 0 but at most e^−708 as well, as negligible to the kernels.

#include <cmath>

#include <Eigen/Core>

#if defined(__AVX2__) && defined(__FMA__) && !defined(__AVX512F__)
#include <immintrin.h>
#define BEMSHAPE_VECTOR_EXPONENTIAL_AVX2 1
#endif

namespace bemshape::linalg {

#if defined(BEMSHAPE_VECTOR_EXPONENTIAL_AVX2)
namespace detail {

/// e^x in each of four lanes (the scheme above).
[[gnu::always_inline]] inline __m256d exponential_lanes(__m256d x) {
  const __m256d low = _mm256_set1_pd(-708.0), high = _mm256_set1_pd(709.0);
  // MAXPD and MINPD return their second operand when either is NaN: a NaN x passes through.
  const __m256d clamped = _mm256_min_pd(high, _mm256_max_pd(low, x));
  // t = x/ln 2 + 1.5·2^52 holds k = round(x/ln 2) in its low mantissa bits.
  const __m256d shift = _mm256_set1_pd(6755399441055744.0);
  const __m256d t = _mm256_fmadd_pd(clamped, _mm256_set1_pd(1.4426950408889634074), shift);
  const __m256d k = _mm256_sub_pd(t, shift);
  __m256d r = _mm256_fnmadd_pd(k, _mm256_set1_pd(6.93147180369123816490e-01), clamped);
  r = _mm256_fnmadd_pd(k, _mm256_set1_pd(1.90821492927058770002e-10), r);
  // e^r = Σ_{n=0}^{12} r^n/n! by Estrin's scheme: pairs, then pairs of pairs in r², r⁴, r⁸
  // (four fused multiply-adds deep instead of Horner's twelve: the kernels around it wait on
  // this chain).
  const auto c = [](double v) { return _mm256_set1_pd(v); };
  const __m256d r2 = _mm256_mul_pd(r, r);
  const __m256d r4 = _mm256_mul_pd(r2, r2);
  const __m256d r8 = _mm256_mul_pd(r4, r4);
  const __m256d q0 = _mm256_fmadd_pd(r, c(1.0), c(1.0));
  const __m256d q1 = _mm256_fmadd_pd(r, c(1.0 / 6.0), c(0.5));
  const __m256d q2 = _mm256_fmadd_pd(r, c(1.0 / 120.0), c(1.0 / 24.0));
  const __m256d q3 = _mm256_fmadd_pd(r, c(1.0 / 5040.0), c(1.0 / 720.0));
  const __m256d q4 = _mm256_fmadd_pd(r, c(1.0 / 362880.0), c(1.0 / 40320.0));
  const __m256d q5 = _mm256_fmadd_pd(r, c(1.0 / 39916800.0), c(1.0 / 3628800.0));
  const __m256d s0 = _mm256_fmadd_pd(q1, r2, q0);
  const __m256d s1 = _mm256_fmadd_pd(q3, r2, q2);
  const __m256d s2 = _mm256_fmadd_pd(q5, r2, q4);
  const __m256d t0 = _mm256_fmadd_pd(s1, r4, s0);
  const __m256d t1 = _mm256_fmadd_pd(c(1.0 / 479001600.0), r4, s2);
  const __m256d p = _mm256_fmadd_pd(t1, r8, t0);
  // 2^k: k + 1023 shifted into the exponent field (|k| ≤ 1023 after the clamp).
  const __m256i biased = _mm256_add_epi64(_mm256_castpd_si256(t), _mm256_set1_epi64x(1023));
  const __m256d scale = _mm256_castsi256_pd(_mm256_slli_epi64(biased, 52));
  const __m256d value = _mm256_mul_pd(p, scale);
  // Zero where x < −708 (not where x is NaN: the comparison is true for unordered operands).
  return _mm256_and_pd(value, _mm256_cmp_pd(x, low, _CMP_NLT_UQ));
}

}  // namespace detail
#endif

/// e^x of every entry of `x` (an Eigen array expression of doubles), as the plain array
/// type `Array`.
template <class Array, class Expression>
[[gnu::always_inline]] inline Array vector_exp(const Expression& x) {
#if defined(BEMSHAPE_VECTOR_EXPONENTIAL_AVX2)
  Array out = x;
  const Eigen::Index n = out.size();
  double* data = out.data();
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4)
    _mm256_storeu_pd(data + i, detail::exponential_lanes(_mm256_loadu_pd(data + i)));
  // (A size known to be a multiple of 4 has no tail; GCC 12 warns about the loop otherwise.)
  if constexpr (Array::SizeAtCompileTime == Eigen::Dynamic || Array::SizeAtCompileTime % 4 != 0)
    for (; i < n; ++i)
      data[i] = std::exp(data[i]);
  return out;
#else
  return Array(x.exp());
#endif
}

}  // namespace bemshape::linalg
