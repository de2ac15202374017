#pragma once
// Coarse-space correction of the transmission system over clusters: A (2N × 2N, tree order,
// bem/solve/hmatrix_transmission_solver.hpp) restricted to densities that are constant on each of
// the clusters C_1 … C_m (the largest clusters of the tree with at most `cluster_size`
// panels),
//
//   A_c = Pᵀ A P,   P = [ E 0 ]     E(i, c) = 1 if panel i ∈ C_c, else 0,
//                       [ 0 E ],
//
// a 2m × 2m Galerkin matrix (test and trial functions: the indicator of a cluster, for φ
// and for q), factorised densely. With the block Jacobi inverse B of
// bem/solve/cluster_block_preconditioner.hpp it makes the two-level preconditioner
//
//   M⁻¹ r = P y + B (r − A P y),   y = A_c⁻¹ Pᵀ r,
//
// (multiplicative: the coarse correction first, the blocks on what it leaves). The blocks
// invert each cluster's own interactions; a density that is smooth across many clusters is
// what they get wrong. For the first-kind operators V0, Vκ, B A acts on a density constant
// over k neighbouring clusters as ≈ √k (‖1_S‖²_V grows as |S|^{3/2}), so without the
// coarse space the largest eigenvalues of A M⁻¹ grow with the number of clusters, and the
// GMRES count with N (docs/benchmarks.md). M⁻¹ A P = P: on the coarse densities the
// preconditioned operator is the identity.
//
// Nothing here multiplies by the full A. A_c is summed from the stored operators (a
// low-rank block U·Vᵀ contributes (EᵀU)(EᵀV)ᵀ, dense blocks and the sparse exterior matrix
// their entries, the mass terms ±½|C_c|), and A P y uses A E kept per block
// (HierarchicalMatrix::group_columns; the sparse Y E). A block meets one or a few clusters,
// so its A E has a few columns where its U has tens: A P y reads a few bytes per row of a
// block, not the factors (which took as long as the block preconditioner and 60 % of a product
// by A on a 10⁵-face box, docs/benchmarks.md).
//
// Precision. By default A E is kept in 8-bit fixed point (each column within 1/254 of its
// largest entry), the sums A_c exactly. The coarse correction then satisfies M⁻¹ A P = P only
// to that accuracy: M is a slightly different fixed linear preconditioner, and GMRES
// converges to the same solution. Measured on the 28596-face remeshed box: 23 iterations
// with A E in 6, 8 or 16 bits or in double precision. O(storage) work to build, 32·m² bytes
// for the LU of A_c, and about one byte per row of each block for A E.

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "bem/solve/cluster_block_preconditioner.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "bem/hmatrix/nested_far_field.hpp"
#include "bem/solve/yukawa_near_field.hpp"

namespace bemshape::bem {

class ClusterCoarseSpace {
 public:
  /// Default cluster size: the preconditioner's blocks (m ≈ N/190 coarse clusters; 2m = 1024
  /// unknowns at 10⁵ faces).
  static constexpr Eigen::Index kDefaultClusterSize = 256;
  /// At most this many clusters: larger meshes use larger clusters, so A_c stays within
  /// 16·(2m)² = 268 MB and its LU within (2/3)(2m)³ ≈ 5·10¹⁰ flops (a few seconds).
  static constexpr Eigen::Index kMaxClusters = 2048;

  /// `laplace`: the H-matrix of [−K0 | V0] (kept by reference: it must outlive this);
  /// `yukawa`: [−Kκ | Vκ] (N × 2N); `half_mass`: ½|T| per panel; all in tree order. The
  /// clusters are the largest with at most `cluster_size` panels, or with twice, four times …
  /// that many if there would be more than kMaxClusters. Scalar: double or float
  /// (instantiated for both).
  /// `storage`: how A E is kept (exact: M⁻¹ A P = P to rounding).
  /// `far`: the part of [−K0 | V0] kept in the H² form (bem/hmatrix/nested_far_field.hpp),
  /// if any, the rest being `laplace` (kept by reference too). Its share of A_c comes from
  /// NestedFarField::grouped_sums, its share of A P y from its product with P y: one H²
  /// product per application, which reads the whole H² part once (at 10⁶ faces about a
  /// sixth of the operators' bytes; the preconditioner stage of that run, 15.3 s for 17
  /// applications, includes it: docs/benchmarks.md, "Fast path at 10⁶ faces").
  template <class Scalar>
  ClusterCoarseSpace(const ClusterTree& tree, const HierarchicalMatrix& laplace,
                     const YukawaNearField<Scalar>& yukawa, const Eigen::VectorXd& half_mass,
                     Eigen::Index cluster_size = kDefaultClusterSize,
                     HierarchicalMatrix::GroupedColumns::Storage storage =
                         HierarchicalMatrix::GroupedColumns::Storage::fixed8,
                     const NestedFarField* far = nullptr);

  /// z = M⁻¹ r = P y + B (r − A P y), y = A_c⁻¹ Pᵀ r, for each column r = (r_φ, r_q) of
  /// `r` (2N × k, tree order); `blocks` is B.
  void apply_two_level(const ClusterBlockPreconditioner& blocks, const Eigen::MatrixXd& r,
                       Eigen::MatrixXd& z) const;

  /// y = A_c⁻¹ Pᵀ r (2m × k).
  Eigen::MatrixXd coarse_solve(const Eigen::MatrixXd& r) const;
  /// A P y (2N × k) from the grouped operators.
  Eigen::MatrixXd apply_operator(const Eigen::MatrixXd& y) const;
  /// z += P y.
  void prolongate_add(const Eigen::MatrixXd& y, Eigen::MatrixXd& z) const;

  /// m, the number of clusters.
  Eigen::Index clusters() const { return clusters_; }
  /// cluster_of()[p]: the coarse cluster of the panel at tree position p (nondecreasing).
  const std::vector<Eigen::Index>& cluster_of() const { return cluster_of_; }
  /// A_c, rows and columns (φ of clusters 1 … m, q of clusters 1 … m), multiplied back from
  /// its LU (only the LU is kept), so to rounding.
  Eigen::MatrixXd matrix() const { return lu_.reconstructedMatrix(); }
  /// Bytes held (the LU of A_c, A E).
  std::uint64_t bytes() const;

 private:
  const HierarchicalMatrix& laplace_;
  const NestedFarField* far_ = nullptr;
  Eigen::Index n_ = 0, clusters_ = 0;
  std::vector<Eigen::Index> cluster_of_;
  HierarchicalMatrix::GroupedColumns laplace_grouped_;  // [−K0 | V0] E
  SparseRowMatrix yukawa_grouped_;                      // [−Kκ | Vκ] (E ⊕ E), N × 2m
  Eigen::VectorXd half_mass_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

}  // namespace bemshape::bem
