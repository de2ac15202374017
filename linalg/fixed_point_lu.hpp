#pragma once
// LU factors with partial pivoting, P M = L U, stored in 16-bit fixed point: a preconditioner's
// block inverse in a quarter of the memory of double-precision factors.
//
// Each column j of the factors is kept in two parts, U's rows 0 … j−1 and L's rows j+1 … n−1
// (L has a unit diagonal), each as q = round(x/s) with s = max|x|/32767; U's diagonal is kept
// apart in single precision, so no pivot is rounded to zero. The stored factors L̃, Ũ are the
// exact LU factors of a nearby matrix:
//   P (M + δM) = L̃ Ũ,   |δM| ≤ |L − L̃||Ũ| + |L||U − Ũ|   (entrywise),
// and every column part is rounded by at most 2^−16 of its largest entry, so ‖δM‖ is about
// 1e−5 of ‖|L||U|‖ — of ‖M‖ up to partial pivoting's growth. solve_in_place applies
// (M + δM)⁻¹ exactly (up to double-precision rounding). For the block preconditioner
// (bem/solve/cluster_block_preconditioner.hpp) that is a block Jacobi preconditioner of blocks
// perturbed by 1e−5 relative, far less than what block Jacobi leaves out: on the benchmarks'
// spheres and thin-walled boxes the GMRES iteration counts and the solutions' agreement with
// the dense path are unchanged (docs/benchmarks.md).

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace bemshape::linalg {

class FixedPointLu {
 public:
  FixedPointLu() = default;
  /// Factorises the square matrix m (Eigen's partial-pivot LU in single precision) and keeps
  /// the factors in fixed point.
  explicit FixedPointLu(const Eigen::MatrixXf& m);

  Eigen::Index size() const { return n_; }
  /// x ← (L̃ Ũ)⁻¹ P x for every column of x (n × k), in double arithmetic.
  void solve_in_place(Eigen::Ref<Eigen::MatrixXd> x) const;
  /// Bytes held: 2 per entry, plus 16 per row for the diagonal, the scales and the pivots.
  std::uint64_t bytes() const;

 private:
  Eigen::Index n_ = 0;
  std::vector<std::int16_t> entries_;  ///< n × n, column-major; diagonal entries unused
  std::vector<float> diagonal_;        ///< U's diagonal
  std::vector<float> upper_scale_, lower_scale_;  ///< per column: its U part, its L part
  std::vector<std::int32_t> order_;    ///< (P x)(i) = x(order_[i])
};

}  // namespace bemshape::linalg
