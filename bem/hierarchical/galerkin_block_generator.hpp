#pragma once
// The operator [−K | V] of one kernel (bem/galerkin_operators.hpp) on the two densities
// (φ, q), served block by block in cluster-tree order for the H-matrix
// (bem/hierarchical/hierarchical_matrix.hpp):
//
//   out(r, c) = −K[τ_r, σ_c],   out(r, |σ| + c) = V[τ_r, σ_c]
//
// with τ_r, σ_c the mesh faces at tree positions row_begin + r, col_begin + c. The entries
// are the dense path's, computed by the same code.

#include <vector>

#include "bem/galerkin_operators.hpp"
#include "bem/hierarchical/cluster_tree.hpp"
#include "bem/hierarchical/hierarchical_matrix.hpp"

namespace bemshape::bem {

template <class Kernel>
class GalerkinBlockGenerator final : public OperatorBlockGenerator {
 public:
  GalerkinBlockGenerator(Kernel kernel, const std::vector<Panel>& panels, const ClusterTree& tree)
      : operators_(kernel, panels), perm_(&tree.permutation()) {}
  int densities() const override { return 2; }
  void fill(Eigen::Index row_begin, Eigen::Index row_end, Eigen::Index col_begin,
            Eigen::Index col_end, Eigen::Ref<Eigen::MatrixXd> out) const override {
    const Eigen::Index n = col_end - col_begin;
    const auto& perm = *perm_;
    for (Eigen::Index c = 0; c < n; ++c)
      for (Eigen::Index r = 0; r < row_end - row_begin; ++r) {
        const auto e = operators_.entry(perm[size_t(row_begin + r)], perm[size_t(col_begin + c)]);
        out(r, c) = -e.double_layer;
        out(r, n + c) = e.single_layer;
      }
  }

 private:
  GalerkinOperators<Kernel> operators_;
  const std::vector<Eigen::Index>* perm_;
};

}  // namespace bemshape::bem
