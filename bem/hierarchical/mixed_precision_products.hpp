#pragma once
// Products of a matrix stored narrow — single precision, or 16-/8-bit fixed point with one
// scale per column (to_fixed_point) — with a few double-precision vectors, in double
// arithmetic and without a widened copy of the matrix:
//   add_scaled_columns:     Y(:, l) += Σ_c s_c·C(c, l)·A(:, c)      (Y += A S C)
//   add_scaled_column_dots: T(c, l) += s_c·Σ_r A(r, c)·X(r, l)      (T += S Aᵀ X)
// for A (rows × cols, column-major with leading dimension lda), S = diag(s) (all ones without
// scales) and k = X.cols() = C.cols() right-hand sides. Each stored column is read once for
// all k of them and widened in registers; the low-rank factors' products
// (adaptive_precision_factors.hpp) and the single-precision near-field blocks
// (hierarchical_matrix.cpp) go through these two functions.
//
// The sums are formed in a fixed order (column by column; each dot product in 8 partial sums
// over rows r ≡ j mod 8, added at the end), so a product is the same on every run and for
// every thread count.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include <Eigen/Core>

namespace bemshape::bem {

namespace mixed_precision_detail {

/// Rows of Y updated per pass over A's columns: the k output segments stay in the first-level
/// cache while every column adds to them.
constexpr Eigen::Index kRowBlock = 256;

/// Eight doubles, one vector register with AVX-512 (two with AVX2): the compiler's generic
/// vectors, so that 8 stored entries are widened and multiplied at once whatever the row
/// count (auto-vectorised loops over short columns fall back to scalar code).
constexpr int kLanes = 8;
typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));

/// Entries r … r + 7 of a stored column, widened to double.
template <class T>
inline Lanes widen(const T* from) {
  typedef T Stored __attribute__((vector_size(kLanes * sizeof(T))));
  Stored v;
  std::memcpy(&v, from, sizeof v);
  return __builtin_convertvector(v, Lanes);
}

inline Lanes load(const double* from) {
  Lanes v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

inline void store(double* to, Lanes v) { std::memcpy(to, &v, sizeof v); }

template <int K, class T>
void add_scaled_columns_k(const T* a, Eigen::Index lda, Eigen::Index rows, Eigen::Index cols,
                          const double* scale, const double* coefficients, Eigen::Index ldc,
                          double* y, Eigen::Index ldy) {
  for (Eigen::Index r0 = 0; r0 < rows; r0 += kRowBlock) {
    const Eigen::Index length = std::min(kRowBlock, rows - r0);
    const Eigen::Index body = length - length % kLanes;
    for (Eigen::Index c = 0; c < cols; ++c) {
      const T* column = a + c * lda + r0;
      const double s = scale ? scale[c] : 1.0;
      double factor[K];
      for (int l = 0; l < K; ++l) factor[l] = s * coefficients[c + l * ldc];
      for (Eigen::Index r = 0; r < body; r += kLanes) {
        const Lanes v = widen(column + r);
        for (int l = 0; l < K; ++l) {
          double* out = y + l * ldy + r0 + r;
          store(out, load(out) + factor[l] * v);
        }
      }
      for (Eigen::Index r = body; r < length; ++r)
        for (int l = 0; l < K; ++l) y[l * ldy + r0 + r] += factor[l] * double(column[r]);
    }
  }
}

template <int K, class T>
void add_scaled_column_dots_k(const T* a, Eigen::Index lda, Eigen::Index rows, Eigen::Index cols,
                              const double* scale, const double* x, Eigen::Index ldx, double* t,
                              Eigen::Index ldt) {
  const Eigen::Index body = rows - rows % kLanes;
  for (Eigen::Index c = 0; c < cols; ++c) {
    const T* column = a + c * lda;
    Lanes partial[K];
    for (int l = 0; l < K; ++l) partial[l] = Lanes{};
    for (Eigen::Index r = 0; r < body; r += kLanes) {
      const Lanes v = widen(column + r);
      for (int l = 0; l < K; ++l) partial[l] += v * load(x + l * ldx + r);
    }
    const double s = scale ? scale[c] : 1.0;
    for (int l = 0; l < K; ++l) {
      double sum = 0.0;
      for (Eigen::Index r = body; r < rows; ++r) sum += double(column[r]) * x[l * ldx + r];
      for (int j = 0; j < kLanes; ++j) sum += partial[l][j];
      t[c + l * ldt] += s * sum;
    }
  }
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

}  // namespace bemshape::bem
