#pragma once
// Products of a matrix stored narrow — single precision, or 16-/8-bit fixed point with one
// scale per column (to_fixed_point) — with a few double-precision vectors, in double
// arithmetic and without a widened copy of the matrix:
//   add_scaled_columns:     Y(:, l) += Σ_c s_c·C(c, l)·A(:, c)      (Y += A S C)
//   add_scaled_column_dots: T(c, l) += s_c·Σ_r A(r, c)·X(r, l)      (T += S Aᵀ X)
// for A (rows × cols, column-major with leading dimension lda), S = diag(s) (all ones without
// scales) and k = X.cols() = C.cols() right-hand sides. Each stored column is read once for
// all k of them and widened in registers; the low-rank factors' products
// (bem/hmatrix/adaptive_precision_factors.hpp) and the single-precision near-field blocks
// (bem/hmatrix/hierarchical_matrix.cpp) go through these two functions.
//
// The sums are formed in a fixed order (each output row over the columns in turn; each dot
// product in one partial sum per vector lane, added at the end), so a product is the same on
// every run and for every thread count (for one build: the lanes depend on the target's
// vector width).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <Eigen/Core>

namespace bemshape::linalg {

namespace mixed_precision_detail {

/// Doubles per vector register of the target (8 with AVX-512, 4 with AVX2, else 2): the
/// compiler's generic vectors, so that the stored entries are widened and multiplied a
/// register at a time whatever the row count (auto-vectorised loops over short columns fall
/// back to scalar code). Wider generic vectors than the registers would be kept in memory.
#if defined(__AVX512F__)
constexpr int kLanes = 8;
#elif defined(__AVX2__)
constexpr int kLanes = 4;
#else
constexpr int kLanes = 2;
#endif
typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));

#if defined(__AVX2__) && !defined(__AVX512F__)
inline Lanes from_register(__m256d v) {
  Lanes out;
  std::memcpy(&out, &v, sizeof out);
  return out;
}
#endif

/// Entries r … r + kLanes − 1 of a stored column, widened to double. Integers are widened to
/// 32 bits by the instruction for it: GCC converts 8- and 16-bit vectors one lane at a time
/// (measured 3–5 times slower than the single-precision columns). With AVX2 the last step to
/// four doubles is one instruction too: GCC's generic conversion does it in two halves of two
/// lanes and joins them (docs/benchmarks.md, "Narrow-format products", has what both changes
/// save).
template <class T>
inline Lanes widen(const T* from) {
#if defined(__AVX2__) && !defined(__AVX512F__)
  if constexpr (std::is_same_v<T, float>)
    return from_register(_mm256_cvtps_pd(_mm_loadu_ps(from)));
#endif
  if constexpr (!std::is_integral_v<T>) {
    typedef T Stored __attribute__((vector_size(kLanes * sizeof(T))));
    Stored v;
    std::memcpy(&v, from, sizeof v);
    return __builtin_convertvector(v, Lanes);
  } else {
    static_assert(sizeof(T) == 1 || sizeof(T) == 2, "8- or 16-bit fixed point");
#if defined(__AVX512F__)
    const __m256i wide = sizeof(T) == 1
                             ? _mm256_cvtepi8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(from)))
                             : _mm256_cvtepi16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(from)));
    // One instruction (the generic conversion takes two halves); the form with a zero source
    // because the plain one trips GCC 12's -Wmaybe-uninitialized.
    const __m512d all = _mm512_mask_cvtepi32_pd(_mm512_setzero_pd(), __mmask8(0xFF), wide);
    Lanes out;
    std::memcpy(&out, &all, sizeof out);
    return out;
#elif defined(__AVX2__)
    std::int32_t four;  // 4 entries of 8 bits
    std::memcpy(&four, from, sizeof four);
    const __m128i wide = sizeof(T) == 1
                             ? _mm_cvtepi8_epi32(_mm_cvtsi32_si128(four))
                             : _mm_cvtepi16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(from)));
    return from_register(_mm256_cvtepi32_pd(wide));
#else
    typedef std::int32_t Wide __attribute__((vector_size(kLanes * sizeof(std::int32_t))));
    Wide w;
    for (int i = 0; i < kLanes; ++i)
      w[i] = from[i];
    return __builtin_convertvector(w, Lanes);
#endif
  }
}

/// How far ahead of the entries in use the kernels ask for a stored column's next bytes. A
/// product reads each block once from memory, and the blocks' columns are short (tens to
/// hundreds of entries) and read several at a time, which the hardware's prefetching follows
/// poorly.
constexpr std::uintptr_t kDotsAhead = 256, kColumnsAhead = 128;

/// Asks for the cache line `bytes` past p. The address is formed as an integer: it may lie
/// past the end of the stored matrix, where a pointer may not point (a prefetch never faults).
inline void prefetch_ahead(const void* p, std::uintptr_t bytes) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(p) + bytes));
}

inline Lanes load(const double* from) {
  Lanes v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

inline void store(double* to, Lanes v) { std::memcpy(to, &v, sizeof v); }

/// Y += A·F with F(c, l) = s_c·C(c, l) formed first. Rows go in chunks of kChunk·kLanes whose
/// K·kChunk sums stay in registers while every column adds to them; Y is read and written once
/// per chunk. The last rows % kLanes rows are summed in scalars.
template <int K, class T>
void add_scaled_columns_k(const T* a, Eigen::Index lda, Eigen::Index rows, Eigen::Index cols,
                          const double* scale, const double* coefficients, Eigen::Index ldc,
                          double* y, Eigen::Index ldy) {
  // K·kChunk sums and kChunk widened entries in registers: 32 of them with AVX-512, 16 else.
  constexpr int kChunk = kLanes == 8 ? 4 : kLanes == 4 ? 2 : 1;
  thread_local std::vector<double> factors;
  factors.resize(static_cast<std::size_t>(cols * K));
  double* f = factors.data();
  for (Eigen::Index c = 0; c < cols; ++c) {
    const double s = scale ? scale[c] : 1.0;
    for (int l = 0; l < K; ++l) f[c * K + l] = s * coefficients[c + l * ldc];
  }
  const auto add_rows = [&]<int R>(Eigen::Index r0, std::integral_constant<int, R>) {
    Lanes sum[K][R];
    for (int l = 0; l < K; ++l)
      for (int i = 0; i < R; ++i) sum[l][i] = Lanes{};
    for (Eigen::Index c = 0; c < cols; ++c) {
      const T* column = a + c * lda + r0;
      prefetch_ahead(column, kColumnsAhead);
      Lanes v[R];
      for (int i = 0; i < R; ++i) v[i] = widen(column + i * kLanes);
      for (int l = 0; l < K; ++l)
        for (int i = 0; i < R; ++i) sum[l][i] += f[c * K + l] * v[i];
    }
    for (int l = 0; l < K; ++l)
      for (int i = 0; i < R; ++i) {
        double* out = y + l * ldy + r0 + i * kLanes;
        store(out, load(out) + sum[l][i]);
      }
  };
  Eigen::Index r0 = 0;
  for (; r0 + kChunk * kLanes <= rows; r0 += kChunk * kLanes)
    add_rows(r0, std::integral_constant<int, kChunk>{});
  for (; r0 + kLanes <= rows; r0 += kLanes) add_rows(r0, std::integral_constant<int, 1>{});
  const Eigen::Index tail = rows - r0;
  if (tail == 0) return;
  double sum[kLanes][K] = {};
  for (Eigen::Index c = 0; c < cols; ++c)
    for (Eigen::Index r = 0; r < tail; ++r)
      for (int l = 0; l < K; ++l) sum[r][l] += f[c * K + l] * double(a[c * lda + r0 + r]);
  for (Eigen::Index r = 0; r < tail; ++r)
    for (int l = 0; l < K; ++l) y[l * ldy + r0 + r] += sum[r][l];
}

/// T += S·Aᵀ·X, kGroup columns at a time so that they share the loads of X; each dot product
/// in kLanes partial sums over rows r ≡ j mod kLanes (then the last rows % kLanes rows),
/// added at the end.
template <int K, class T>
void add_scaled_column_dots_k(const T* a, Eigen::Index lda, Eigen::Index rows, Eigen::Index cols,
                              const double* scale, const double* x, Eigen::Index ldx, double* t,
                              Eigen::Index ldt) {
  constexpr int kGroup = 4;
  const Eigen::Index body = rows - rows % kLanes;
  const auto add_columns = [&]<int G>(Eigen::Index c0, std::integral_constant<int, G>) {
    Lanes partial[G][K];
    for (int j = 0; j < G; ++j)
      for (int l = 0; l < K; ++l) partial[j][l] = Lanes{};
    for (Eigen::Index r = 0; r < body; r += kLanes) {
      Lanes xv[K];
      for (int l = 0; l < K; ++l) xv[l] = load(x + l * ldx + r);
      for (int j = 0; j < G; ++j) {
        prefetch_ahead(a + (c0 + j) * lda + r, kDotsAhead);
        const Lanes v = widen(a + (c0 + j) * lda + r);
        for (int l = 0; l < K; ++l) partial[j][l] += v * xv[l];
      }
    }
    for (int j = 0; j < G; ++j) {
      const T* column = a + (c0 + j) * lda;
      const double s = scale ? scale[c0 + j] : 1.0;
      for (int l = 0; l < K; ++l) {
        double sum = 0.0;
        for (Eigen::Index r = body; r < rows; ++r) sum += double(column[r]) * x[l * ldx + r];
        for (int i = 0; i < kLanes; ++i) sum += partial[j][l][i];
        t[c0 + j + l * ldt] += s * sum;
      }
    }
  };
  Eigen::Index c0 = 0;
  for (; c0 + kGroup <= cols; c0 += kGroup) add_columns(c0, std::integral_constant<int, kGroup>{});
  for (; c0 < cols; ++c0) add_columns(c0, std::integral_constant<int, 1>{});
}

/// Calls run(K, l) for the right-hand sides l … l + K − 1, four at a time (K a compile-time
/// constant, std::integral_constant<int, K>): the kernels keep K sums in registers.
template <class Run>
void in_groups_of_four(Eigen::Index columns, Run&& run) {
  for (Eigen::Index l = 0; l < columns;) {
    const Eigen::Index k = std::min<Eigen::Index>(4, columns - l);
    switch (k) {
      case 1: run(std::integral_constant<int, 1>{}, l); break;
      case 2: run(std::integral_constant<int, 2>{}, l); break;
      case 3: run(std::integral_constant<int, 3>{}, l); break;
      default: run(std::integral_constant<int, 4>{}, l); break;
    }
    l += k;
  }
}

}  // namespace mixed_precision_detail

/// x in fixed point: q_r = round(x_r/s), s = max|x|/(2^{b−1} − 1), b the width of Int. Writes q
/// (if not null) and s; returns the rounding error ‖x − s q‖ (0 for a zero column).
template <class Int>
double to_fixed_point(const Eigen::Ref<const Eigen::VectorXd>& x, Int* q, double& scale) {
  const double largest = x.cwiseAbs().maxCoeff();
  scale = largest / double(std::numeric_limits<Int>::max());
  if (!(scale > 0.0)) {
    if (q) std::fill(q, q + x.size(), Int(0));
    scale = 0.0;
    return 0.0;
  }
  double error2 = 0.0;
  for (Eigen::Index r = 0; r < x.size(); ++r) {
    const double level = std::nearbyint(x(r) / scale);
    if (q) q[r] = static_cast<Int>(level);
    const double e = x(r) - scale * level;
    error2 += e * e;
  }
  return std::sqrt(error2);
}

/// Y += A·diag(s)·C: A is rows × cols at `a` (column-major, leading dimension lda; float,
/// int16_t or int8_t), s the columns' scales (nullptr: all ones), C cols × k, Y rows × k.
template <class T>
void add_scaled_columns(const T* a, Eigen::Index lda, Eigen::Index rows, Eigen::Index cols,
                        const double* scale, const Eigen::Ref<const Eigen::MatrixXd>& c,
                        Eigen::Ref<Eigen::MatrixXd> y) {
  using namespace mixed_precision_detail;
  in_groups_of_four(c.cols(), [&](auto k, Eigen::Index l) {
    add_scaled_columns_k<decltype(k)::value>(a, lda, rows, cols, scale, c.data() + l * c.outerStride(),
                                            c.outerStride(), y.data() + l * y.outerStride(), y.outerStride());
  });
}

/// T += diag(s)·Aᵀ·X: A as for add_scaled_columns, X rows × k, T cols × k.
template <class T>
void add_scaled_column_dots(const T* a, Eigen::Index lda, Eigen::Index rows, Eigen::Index cols,
                            const double* scale, const Eigen::Ref<const Eigen::MatrixXd>& x,
                            Eigen::Ref<Eigen::MatrixXd> t) {
  using namespace mixed_precision_detail;
  in_groups_of_four(x.cols(), [&](auto k, Eigen::Index l) {
    add_scaled_column_dots_k<decltype(k)::value>(a, lda, rows, cols, scale, x.data() + l * x.outerStride(),
                                                x.outerStride(), t.data() + l * t.outerStride(), t.outerStride());
  });
}

}  // namespace bemshape::linalg
