#pragma once
// Block-Jacobi preconditioner of the transmission system over clusters: for each cluster C
// of at most `block_size` panels (the largest such clusters of the tree, which tile all
// panels), the system restricted to the unknowns (φ_C, q_C),
//
//   [ −½M_C − K0[C,C]    V0[C,C] ]
//   [  ½M_C − Kκ[C,C]    Vκ[C,C] ]
//
// is factorised (partial-pivot LU) and M⁻¹ applies the inverses block by block. The
// restriction captures every interaction closer than about the cluster size, where the
// first-kind operators V0, Vκ are dominated by their singular, mesh-scale part; the Krylov
// solver is left with the smooth far interactions.
//
// The factors are computed in single precision and stored in 16-bit fixed point
// (linalg/fixed_point_lu.hpp): memory at most 8·N·block_size bytes. A preconditioner only has to be
// close to the inverse: the stored factors are the exact factors of blocks perturbed by
// about 1e−5 relative, far less than the block Jacobi approximation leaves out, and GMRES
// measures the residual of the double-precision system, so the solution's accuracy does not
// depend on it. (Single-precision factors take twice the memory for the same iteration
// counts: docs/benchmarks.md, "Memory".)

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "bem/hmatrix/cluster_tree.hpp"
#include "linalg/fixed_point_lu.hpp"
#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "bem/solve/yukawa_near_field.hpp"

namespace bemshape::bem {

class ClusterBlockPreconditioner {
 public:
  /// Default cluster size: measured on spheres and plates (docs/benchmarks.md), iteration
  /// counts fall slowly beyond it while the factorisations grow as the cube.
  static constexpr Eigen::Index kDefaultBlockSize = 256;

  /// `laplace`: the H-matrix of [−K0 | V0]; `yukawa`: [−Kκ | Vκ] (N × 2N); `half_mass`:
  /// ½|T| per panel; all in tree order. Scalar: double or float (instantiated for both).
  template <class Scalar>
  ClusterBlockPreconditioner(const ClusterTree& tree, const HierarchicalMatrix& laplace,
                             const YukawaNearField<Scalar>& yukawa, const Eigen::VectorXd& half_mass,
                             Eigen::Index block_size = kDefaultBlockSize);

  /// z = M⁻¹ r for each column r = (r_φ, r_q) of `r` (2N × k, tree order); one pass over
  /// the factors for all k columns.
  void apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const;

  /// Bytes held by the factorisations.
  std::uint64_t bytes() const;

  /// Bytes the preconditioner of N panels will hold at most.
  static std::uint64_t bytes_for(Eigen::Index panels, Eigen::Index block_size) {
    return 8ull * std::uint64_t(panels) * std::uint64_t(block_size) + 32ull * std::uint64_t(panels);
  }

 private:
  Eigen::Index n_ = 0;
  std::vector<std::pair<Eigen::Index, Eigen::Index>> ranges_;
  std::vector<linalg::FixedPointLu> factors_;
};

}  // namespace bemshape::bem
