#pragma once
// The operator [−K | V] of one kernel (bem/operators/galerkin_operators.hpp) on the two
// densities (φ, q), served block by block (bem/operators/operator_block_generator.hpp) in a
// given order of the faces, for the compressed assembly (the H-matrix's tree order,
// ClusterTree::permutation):
//
//   out(r, c) = −K[τ_r, σ_c],   out(r, |σ| + c) = V[τ_r, σ_c]
//
// with τ_r, σ_c the mesh faces at positions row_begin + r, col_begin + c of that order. The
// entries are the dense path's, computed by the same code (GalerkinOperators::fill_range) on
// a copy of the panels in that order, so that the rows and columns of a block are
// consecutive panels and its far-field pairs load straight into SIMD lanes.

#include <vector>

#include <Eigen/Core>

#include "bem/operators/galerkin_operators.hpp"
#include "bem/operators/operator_block_generator.hpp"
#include "bem/quadrature/panel.hpp"

namespace bemshape::bem {

template <class Kernel>
class GalerkinBlockGenerator final : public OperatorBlockGenerator {
 public:
  /// The operators of `kernel` on `panels` (one per mesh face) in the order `faces`: the
  /// face at each position (kept by reference; e.g. ClusterTree::permutation()).
  /// `single_precision`: the entries are stored in single precision, and the Laplace panel
  /// integrals need only kSinglePrecisionRuleAccuracy (GalerkinOperators::set_laplace_accuracy).
  GalerkinBlockGenerator(Kernel kernel, const std::vector<Panel>& panels,
                         const std::vector<Eigen::Index>& faces, bool single_precision = false)
      : ordered_(in_order(panels, faces)), operators_(kernel, ordered_, &faces) {
    if (single_precision) operators_.set_laplace_accuracy(kSinglePrecisionRuleAccuracy);
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
  static std::vector<Panel> in_order(const std::vector<Panel>& panels,
                                     const std::vector<Eigen::Index>& faces) {
    std::vector<Panel> ordered;
    ordered.reserve(panels.size());
    for (const Eigen::Index face : faces) ordered.push_back(panels[static_cast<std::size_t>(face)]);
    return ordered;
  }

  std::vector<Panel> ordered_;  ///< panels[faces[i]] at i
  GalerkinOperators<Kernel> operators_;
};

}  // namespace bemshape::bem
