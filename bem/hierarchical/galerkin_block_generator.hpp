#pragma once
// The operator [−K | V] of one kernel (bem/galerkin_operators.hpp) on the two densities
// (φ, q), served block by block in cluster-tree order for the H-matrix
// (bem/hierarchical/hierarchical_matrix.hpp):
//
//   out(r, c) = −K[τ_r, σ_c],   out(r, |σ| + c) = V[τ_r, σ_c]
//
// with τ_r, σ_c the mesh faces at tree positions row_begin + r, col_begin + c. The entries
// are the dense path's, computed by the same code (GalerkinOperators::fill_range) on a copy
// of the panels in tree order, so that the rows and columns of a block are consecutive
// panels and its far-field pairs load straight into SIMD lanes.

#include <vector>

#include "bem/galerkin_operators.hpp"
#include "bem/hierarchical/cluster_tree.hpp"
#include "bem/hierarchical/hierarchical_matrix.hpp"

namespace bemshape::bem {

template <class Kernel>
class GalerkinBlockGenerator final : public OperatorBlockGenerator {
 public:
  GalerkinBlockGenerator(Kernel kernel, const std::vector<Panel>& panels, const ClusterTree& tree)
      : tree_ordered_(tree_order(panels, tree)), operators_(kernel, tree_ordered_, &tree.permutation()) {
    operators_.tabulate_touching_pairs();
  }
  int densities() const override { return 2; }
  void fill(Eigen::Index row_begin, Eigen::Index row_end, Eigen::Index col_begin,
            Eigen::Index col_end, Eigen::Ref<Eigen::MatrixXd> out) const override {
    const Eigen::Index n = col_end - col_begin;
    operators_.fill_range(row_begin, row_end, col_begin, col_end, out.rightCols(n), out.leftCols(n));
    out.leftCols(n) *= -1.0;
  }

 private:
  static std::vector<Panel> tree_order(const std::vector<Panel>& panels, const ClusterTree& tree) {
    std::vector<Panel> ordered;
    ordered.reserve(panels.size());
    for (const Eigen::Index face : tree.permutation()) ordered.push_back(panels[static_cast<std::size_t>(face)]);
    return ordered;
  }

  std::vector<Panel> tree_ordered_;  ///< panels[permutation[i]] at i
  GalerkinOperators<Kernel> operators_;
};

}  // namespace bemshape::bem
