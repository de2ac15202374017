#pragma once
// The exterior (Yukawa) operators as one sparse matrix. Gκ = e^{−κr}/(4πr) decays
// exponentially, so a row needs only the panels near its own: the pair (i, j) is kept when
// the gap between the panels' bounding balls, |c_i − c_j| − r_i − r_j (centroids c, radii r
// about them), is within the cutoff distance
//   R* = −ln(ε)/κ   (18.4/κ at ε = 1e−8; 23/κ at the dense path's 1e−10),
// and everything farther is dropped (a test between centroids alone would drop touching
// panels larger than R*, as a graded mesh's are). What that drops is a fraction ε of each row's sum:
// on a plane, ∫_{r>R} e^{−κr}/(4πr) 2πr dr = e^{−κR}/(2κ) is e^{−κR} times the whole
// integral 1/(2κ), and a second wall at distance t (a thin part) adds at most as much
// again, e^{−κR}/(2κ) of its e^{−κt}/(2κ); the double layer's kernel decays as fast
// (tests/bem/solve/test_yukawa_near_field.cpp measures the dropped part of each
// row). The dense path drops less (an entry when e^{−κ·gap} < 1e−10 for the gap
// |c_i − c_j| − r_i − r_j between the panels, bem/operators/galerkin_operators.hpp), so every pair
// kept here is an entry it holds too, with the same value. A panel interacts with the
// panels within R* of it, O(1) of them per row whatever N, so the matrix has O(N) entries.
//
// Layout, in cluster-tree order (bem/hmatrix/cluster_tree.hpp): N × 2N,
//   Y(i, j) = −Kκ[i, j],   Y(i, N + j) = Vκ[i, j],
// i.e. the exterior identity's operator on (φ, q) without the ½M term, stored as pairs
// whose columns are kept as runs of consecutive panels (YukawaNearField).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/quadrature/panel.hpp"
#include "core/assert.hpp"
#include "core/progress.hpp"

namespace bemshape::bem {

/// An Eigen sparse matrix with 32-bit indices, row-major (the coarse space's grouped
/// exterior operator).
using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int32_t>;

/// The size of each row of Y, in tree order: its pairs, and the runs of consecutive
/// columns they form (what YukawaNearField stores in place of one index per pair).
struct YukawaNearFieldRows {
  Eigen::VectorX<Eigen::Index> pairs, runs;
};

/// Y = [−Kκ | Vκ] in compressed rows with one column pattern for both operators: slot s of
/// row i holds a panel j and both entries of the pair, −Kκ[i, j] and Vκ[i, j] (one panel
/// pair gives both). The columns of a row are stored as runs of consecutive panels — a
/// 32-bit first column and a 16-bit length — since the panels within the cutoff of a
/// panel fill whole stretches of tree order: about 7–8 pairs per run on a sphere and a
/// thin-walled box, so a pair costs its two values and under a byte of index, 9 bytes in
/// single precision (12 with one 32-bit index per pair). Kκ vanishes between coplanar
/// panels; its zeros are stored with their Vκ. The pairs are O(N) (about 650 per row at
/// the default element size), so 2^31 − 1 of them is ample up to 10⁶ faces; assembly
/// refuses a matrix with more.
///
/// `Scalar`: double, or float for the H-matrix solver when its factors are in single
/// precision (tolerance ≥ 1e−6): each entry is computed in double precision and rounded
/// once, 6e−8 relative, the rounding of the interior part's single-precision blocks.
template <class Scalar>
class YukawaNearField {
 public:
  /// Longest run: a longer stretch of consecutive columns is stored as several runs.
  static constexpr Eigen::Index kMaxRun = 65535;

  YukawaNearField() = default;
  /// Room for rows.pairs(i) pairs in rows.runs(i) runs in row i (all zero): the rows are then
  /// filled in place (set_columns and the value arrays).
  explicit YukawaNearField(const YukawaNearFieldRows& rows)
      : n_(rows.pairs.size()),
        row_start_(static_cast<std::size_t>(n_) + 1, 0),
        run_row_start_(static_cast<std::size_t>(n_) + 1, 0) {
    for (Eigen::Index i = 0; i < n_; ++i) {
      row_start_[std::size_t(i) + 1] = row_start_[std::size_t(i)] + rows.pairs(i);
      run_row_start_[std::size_t(i) + 1] = run_row_start_[std::size_t(i)] + rows.runs(i);
    }
    run_column_.assign(std::size_t(run_row_start_.back()), 0);
    run_length_.assign(std::size_t(run_row_start_.back()), 0);
    minus_double_layer_.assign(std::size_t(row_start_.back()), Scalar(0));
    single_layer_.assign(std::size_t(row_start_.back()), Scalar(0));
  }

  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return 2 * n_; }
  Eigen::Index pairs() const { return row_start_.empty() ? 0 : row_start_.back(); }
  Eigen::Index runs() const { return run_row_start_.empty() ? 0 : run_row_start_.back(); }
  /// Slots [row_begin(i), row_end(i)) of the values hold row i's pairs, in column order.
  Eigen::Index row_begin(Eigen::Index i) const { return row_start_[std::size_t(i)]; }
  Eigen::Index row_end(Eigen::Index i) const { return row_start_[std::size_t(i) + 1]; }
  /// Runs [run_begin(i), run_end(i)) hold row i's columns: run r covers the columns
  /// run_column(r) … run_column(r) + run_length(r) − 1, in consecutive slots.
  Eigen::Index run_begin(Eigen::Index i) const { return run_row_start_[std::size_t(i)]; }
  Eigen::Index run_end(Eigen::Index i) const { return run_row_start_[std::size_t(i) + 1]; }
  Eigen::Index run_column(Eigen::Index r) const { return run_column_[std::size_t(r)]; }
  Eigen::Index run_length(Eigen::Index r) const { return run_length_[std::size_t(r)]; }

  /// f(first column, length) for each run of strictly increasing `columns`: the maximal
  /// stretches of consecutive columns, split where one would exceed kMaxRun.
  template <class F>
  static void for_each_run(const std::vector<Eigen::Index>& columns, F&& f) {
    for (std::size_t t = 0; t < columns.size();) {
      std::size_t u = t + 1;
      while (u < columns.size() && columns[u] == columns[u - 1] + 1 && Eigen::Index(u - t) < kMaxRun) ++u;
      f(columns[t], Eigen::Index(u - t));
      t = u;
    }
  }

  /// Stores the columns of row i (strictly increasing, as many as counted) as runs.
  void set_columns(Eigen::Index i, const std::vector<Eigen::Index>& columns) {
    BEMSHAPE_ASSERT(Eigen::Index(columns.size()) == row_end(i) - row_begin(i),
                    "exterior near field: the row holds the counted pairs");
    Eigen::Index r = run_begin(i);
    for_each_run(columns, [&](Eigen::Index first, Eigen::Index length) {
      BEMSHAPE_ASSERT(r < run_end(i), "exterior near field: the row holds the counted runs");
      run_column_[std::size_t(r)] = static_cast<std::int32_t>(first);
      run_length_[std::size_t(r)] = static_cast<std::uint16_t>(length);
      ++r;
    });
    BEMSHAPE_ASSERT(r == run_end(i), "exterior near field: the row holds the counted runs");
  }

  Scalar* minus_double_layer() { return minus_double_layer_.data(); }
  Scalar* single_layer() { return single_layer_.data(); }
  const Scalar* minus_double_layer() const { return minus_double_layer_.data(); }
  const Scalar* single_layer() const { return single_layer_.data(); }

  /// The slot of column j in row i, −1 if row i does not hold it.
  Eigen::Index slot(Eigen::Index i, Eigen::Index j) const {
    Eigen::Index s = row_begin(i);
    for (Eigen::Index r = run_begin(i); r < run_end(i); ++r) {
      if (j < run_column(r)) return -1;
      if (j < run_column(r) + run_length(r)) return s + (j - run_column(r));
      s += run_length(r);
    }
    return -1;
  }

  /// f(j, −Kκ[i, j], Vκ[i, j]) for the pairs of row i, j increasing.
  template <class F>
  void for_each_in_row(Eigen::Index i, F&& f) const {
    Eigen::Index s = row_begin(i);
    for (Eigen::Index r = run_begin(i); r < run_end(i); ++r)
      for (Eigen::Index j = run_column(r); j < run_column(r) + run_length(r); ++j, ++s)
        f(j, double(minus_double_layer_[std::size_t(s)]), double(single_layer_[std::size_t(s)]));
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

  /// Bytes of a matrix of `pairs` pairs in `runs` runs over `rows` rows: per pair two values,
  /// per run a 32-bit column and a 16-bit length, and the two row offset arrays.
  static std::uint64_t bytes_for(std::uint64_t pairs, std::uint64_t runs, Eigen::Index rows) {
    return 2ull * sizeof(Scalar) * pairs + 6ull * runs + 16ull * std::uint64_t(rows + 1);
  }
  /// Bytes held.
  std::uint64_t bytes() const { return bytes_for(std::uint64_t(pairs()), std::uint64_t(runs()), n_); }

 private:
  Eigen::Index n_ = 0;
  std::vector<Eigen::Index> row_start_, run_row_start_;
  std::vector<std::int32_t> run_column_;
  std::vector<std::uint16_t> run_length_;
  std::vector<Scalar> minus_double_layer_, single_layer_;
};

/// Whether the pair (a, b) is coplanar (normals parallel to 1e−12, each centroid within 1e−9
/// of the larger diameter of the other's plane; symmetric in a and b) and does not touch: then
/// Kκ vanishes both ways and Vκ[a, b] = Vκ[b, a], so the single-precision assembly computes
/// the pair once, in the row of the panel first in tree order, and mirrors it into the other
/// (assemble_yukawa_near_field). On the flat walls of the wall reading's meshes these are a
/// quarter of the time of the pairs that do not touch.
inline bool mirrored_coplanar_pair(const Panel& a, const Panel& b) {
  const double tolerance = 1e-9 * std::max(a.diameter, b.diameter);
  const Eigen::Vector3d offset = b.centroid - a.centroid;
  return std::abs(a.normal.dot(b.normal)) > 1.0 - 1e-12 && std::abs(offset.dot(a.normal)) <= tolerance &&
         std::abs(offset.dot(b.normal)) <= tolerance &&
         !GalerkinOperators<YukawaKernel>::touching(a, b);
}

/// The runs of consecutive columns in strictly increasing `columns`, as set_columns stores
/// them (runs no longer than YukawaNearField's kMaxRun).
Eigen::Index yukawa_near_field_runs(const std::vector<Eigen::Index>& columns);

/// The accuracy of the Yukawa entries that do not touch (relative to an unattenuated entry,
/// GalerkinOperators::set_yukawa_accuracy) when they are stored in single precision:
/// rounding to float already moves the largest entries by up to 2⁻²⁴ ≈ 6e−8 of themselves,
/// so the 1e−9 of YukawaAttenuation::absolute_accuracy would buy nothing. It sets the polar
/// scheme's resolution, the attenuated Gauss rules (single_precision_attenuated_rules) and
/// the attenuated pairs' collapsed rules; the touching pairs and the outer rules keep
/// theirs. The tube of the wall-reading bench: exterior near field 2.3–2.9 → 1.7 s on one
/// thread from the polar scheme's share, walls unchanged (docs/quadrature.md, "Near targets
/// of panels many 1/κ across").
inline constexpr double kSinglePrecisionYukawaAccuracy = kSinglePrecisionRuleAccuracy;

/// The gap between two panels' bounding balls beyond which the pair is dropped,
/// R* = −ln(negligible)/κ [model units]: the dropped part of a row is about `negligible` of its sum (see the top of this
/// file).
double yukawa_cutoff_distance(double kappa, double negligible);

/// The number of pairs each row of Y will hold, in tree order (one per panel within the
/// cutoff), and the runs they form. The candidate search only, no integrals: what the
/// memory guard needs before anything is assembled. About 650 per row at the default element size κ·h = 3 on a
/// curved surface; it grows as (κ·h)^−2 on finer meshes and doubles on walls thinner than
/// the cutoff.
YukawaNearFieldRows yukawa_near_field_rows(const std::vector<Panel>& panels, const ClusterTree& tree,
                                           double kappa, double negligible);

/// Assembles Y for the panels in tree order (parallel over rows; each row is computed the
/// same way whatever the thread count). Pairs whose bounding balls are farther apart than
/// R* = −ln(negligible)/κ are dropped (about `negligible` of each row's sum); the default is
/// the dense path's threshold, larger values (the H-matrix solver passes ε) trade parts of
/// the rows below the compression tolerance for fewer pairs. If the counted pairs do not fit in the memory the machine has
/// left (core/memory.hpp), ResourceError before any is stored. The rows are written in place
/// into storage of the counted size, so nothing else of the matrix's size is ever held.
/// `rows`: yukawa_near_field_rows of the same arguments, if already counted. `accuracy`: of
/// the entries that do not touch (GalerkinOperators::set_yukawa_accuracy); by default
/// kSinglePrecisionYukawaAccuracy in single precision, YukawaAttenuation::absolute_accuracy
/// in double.
template <class Scalar = double>
YukawaNearField<Scalar> assemble_yukawa_near_field(
    const std::vector<Panel>& panels, const ClusterTree& tree, double kappa,
    double negligible = YukawaAttenuation::negligible, const ProgressCallback& progress = {},
    const YukawaNearFieldRows* rows = nullptr,
    double accuracy = std::is_same_v<Scalar, float> ? kSinglePrecisionYukawaAccuracy
                                                    : YukawaAttenuation::absolute_accuracy);

}  // namespace bemshape::bem
