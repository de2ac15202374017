#pragma once
// The exterior (Yukawa) operators as one sparse matrix. Gκ = e^{−κr}/(4πr) decays
// exponentially, so a Galerkin entry between panels whose gap exceeds
// g* = −ln(YukawaAttenuation::negligible)/κ ≈ 23/κ is below 1e−10 of an unattenuated
// entry and is zero in the dense path too (bem/galerkin_operators.hpp): with that threshold
// storing only the rest loses nothing the dense path keeps; the H-matrix solver derives the
// threshold from its compression tolerance instead. A panel interacts with the panels within about
// g* + its size, O(1) of them per row whatever N, so the matrix has O(N) entries.
//
// Layout, in cluster-tree order (bem/hierarchical/cluster_tree.hpp): N × 2N,
//   Y(i, j) = −Kκ[i, j],   Y(i, N + j) = Vκ[i, j],
// i.e. the exterior identity's operator on (φ, q) without the ½M term, stored as pairs
// (YukawaNearField).

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "bem/galerkin_operators.hpp"
#include "bem/hierarchical/cluster_tree.hpp"
#include "bem/panel.hpp"
#include "core/progress.hpp"

namespace bemshape::bem {

/// An Eigen sparse matrix with 32-bit indices, row-major (the coarse space's grouped
/// exterior operator).
using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int32_t>;

/// Y = [−Kκ | Vκ] in compressed rows with one column pattern for both operators: slot s of
/// row i holds the panel j = column(s) and both entries of the pair, −Kκ[i, j] and Vκ[i, j]
/// (one panel pair gives both). A pair costs one 32-bit index and two values: 12 bytes in
/// single precision, 20 in double, instead of 16 and 24 as two separate sparse entries.
/// Kκ vanishes between coplanar panels; its zeros are stored with their Vκ. The pairs are
/// O(N) (about 650 per row at the default element size), so 2^31 − 1 of them is ample up to
/// 10⁶ faces; assembly refuses a matrix with more.
///
/// `Scalar`: double, or float for the H-matrix solver when its factors are in single
/// precision (tolerance ≥ 1e−6): each entry is computed in double precision and rounded
/// once, 6e−8 relative, the rounding of the interior part's single-precision blocks.
template <class Scalar>
class YukawaNearField {
 public:
  YukawaNearField() = default;
  /// Room for row_pairs(i) pairs in row i (all zero): the rows are then filled in place.
  explicit YukawaNearField(const Eigen::VectorX<Eigen::Index>& row_pairs)
      : n_(row_pairs.size()), row_start_(static_cast<std::size_t>(n_) + 1, 0) {
    for (Eigen::Index i = 0; i < n_; ++i)
      row_start_[std::size_t(i) + 1] = row_start_[std::size_t(i)] + row_pairs(i);
    column_.assign(std::size_t(row_start_.back()), 0);
    minus_double_layer_.assign(std::size_t(row_start_.back()), Scalar(0));
    single_layer_.assign(std::size_t(row_start_.back()), Scalar(0));
  }

  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return 2 * n_; }
  Eigen::Index pairs() const { return row_start_.empty() ? 0 : row_start_.back(); }
  Eigen::Index row_begin(Eigen::Index i) const { return row_start_[std::size_t(i)]; }
  Eigen::Index row_end(Eigen::Index i) const { return row_start_[std::size_t(i) + 1]; }

  std::int32_t* column() { return column_.data(); }
  Scalar* minus_double_layer() { return minus_double_layer_.data(); }
  Scalar* single_layer() { return single_layer_.data(); }
  const std::int32_t* column() const { return column_.data(); }
  const Scalar* minus_double_layer() const { return minus_double_layer_.data(); }
  const Scalar* single_layer() const { return single_layer_.data(); }

  /// f(j, −Kκ[i, j], Vκ[i, j]) for the pairs of row i, j increasing.
  template <class F>
  void for_each_in_row(Eigen::Index i, F&& f) const {
    for (Eigen::Index s = row_begin(i); s < row_end(i); ++s)
      f(Eigen::Index(column_[std::size_t(s)]), double(minus_double_layer_[std::size_t(s)]),
        double(single_layer_[std::size_t(s)]));
  }

  /// The n × 2n matrix [−Kκ | Vκ] (tests, small meshes).
  Eigen::MatrixXd to_dense() const {
    Eigen::MatrixXd y = Eigen::MatrixXd::Zero(n_, 2 * n_);
    for (Eigen::Index i = 0; i < n_; ++i)
      for_each_in_row(i, [&](Eigen::Index j, double minus_k, double v) {
        y(i, j) = minus_k;
        y(i, n_ + j) = v;
      });
    return y;
  }

  /// Bytes held: per pair an index and two values, and the row offsets.
  std::uint64_t bytes() const {
    return (4ull + 2ull * sizeof(Scalar)) * std::uint64_t(pairs()) +
           8ull * std::uint64_t(row_start_.size());
  }

 private:
  Eigen::Index n_ = 0;
  std::vector<Eigen::Index> row_start_;
  std::vector<std::int32_t> column_;
  std::vector<Scalar> minus_double_layer_, single_layer_;
};

/// The gap beyond which Yukawa entries attenuated below `negligible` are dropped,
/// g* = −ln(negligible)/κ [model units].
double yukawa_cutoff_gap(double kappa, double negligible);

/// The number of pairs each row of Y will hold, in tree order: one per panel within the
/// cutoff. The candidate search only, no integrals: what the memory guard needs before
/// anything is assembled. About 650 per row at the default element size κ·h = 3 on a
/// curved surface; it grows as (κ·h)^−2 on finer meshes and doubles on walls thinner than
/// the cutoff.
Eigen::VectorX<Eigen::Index> yukawa_near_field_row_pairs(const std::vector<Panel>& panels,
                                                         const ClusterTree& tree, double kappa,
                                                         double negligible);

/// Assembles Y for the panels in tree order (parallel over rows; each row is computed the
/// same way whatever the thread count). Pairs of panels whose gap |c_j − c_k| − r_j − r_k
/// gives e^{−κ·gap} < `negligible` are dropped; the default is the dense path's threshold,
/// larger values (the H-matrix solver passes ε) trade entries below the compression
/// tolerance for fewer pairs. If the counted pairs do not fit in the memory the machine has
/// left (core/memory.hpp), ResourceError before any is stored. The rows are written in place
/// into storage of the counted size, so nothing else of the matrix's size is ever held.
/// `row_pairs`: yukawa_near_field_row_pairs of the same arguments, if already counted.
template <class Scalar = double>
YukawaNearField<Scalar> assemble_yukawa_near_field(
    const std::vector<Panel>& panels, const ClusterTree& tree, double kappa,
    double negligible = YukawaAttenuation::negligible, const ProgressCallback& progress = {},
    const Eigen::VectorX<Eigen::Index>* row_pairs = nullptr);

}  // namespace bemshape::bem
