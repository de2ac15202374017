#pragma once
// The entries of an operator served block by block: what every compressed assembly reads
// (bem/hmatrix/hierarchical_matrix.hpp, bem/hmatrix/nested_far_field.hpp), so that it is
// written once for every operator. GalerkinBlockGenerator
// (bem/operators/galerkin_block_generator.hpp) serves the Galerkin entries of the dense path.

#include <Eigen/Core>

namespace bemshape::bem {

/// Entries of the operator, in its row and column order (for the H-matrix: tree order):
/// out(o·|τ| + r, d·|σ| + c) = A_{o,d}(τ_begin + r, σ_begin + c) for the row elements
/// τ = [row_begin, row_end), the column elements σ = [col_begin, col_end), output
/// o < outputs() (e.g. a potential and its gradient at a target point) and density
/// d < densities(); `out` is outputs()·|τ| × densities()·|σ|.
class OperatorBlockGenerator {
 public:
  virtual ~OperatorBlockGenerator() = default;
  virtual int densities() const = 0;
  virtual int outputs() const { return 1; }
  virtual void fill(Eigen::Index row_begin, Eigen::Index row_end, Eigen::Index col_begin,
                    Eigen::Index col_end, Eigen::Ref<Eigen::MatrixXd> out) const = 0;
};

}  // namespace bemshape::bem
