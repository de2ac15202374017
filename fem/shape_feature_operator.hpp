#pragma once
// The discrete shape-feature operator on a voxel grid (Q1 elements, see q1_element.hpp):
//
//   A_pq = ã ∫ ∇φ_p·∇φ_q + ∫ c(x) φ_p φ_q,     c = α(1 − χ) per cell,
//
// the bilinear form of the weak problem (paper, section "Formulation")
//
//   ∫ ã ∇s_i·∇ξ + α ∫ (1 − χ) s_i ξ = ∫ χ e_i·∇ξ   for all ξ ∈ H¹₀(Ω_R),
//
// restricted to the interior nodes (s = 0 on ∂Ω_R). ã is constant, so only the reaction
// coefficient c varies from cell to cell. The operator is matrix-free: at node p the 3^D
// stencil entries are A(o) = ã·Σ_{cells ∋ p, p+o} K_e(o) + Σ_{cells ∋ p, p+o} c_e·M_e(o), formed
// on the fly from the 2^D cell coefficients around p, so a grid of N nodes costs O(N) memory.
//
// Vectors are #nodes×m matrices (one column per right-hand side, node numbering of
// voxel_grid.hpp); rows of boundary nodes are zero on output and ignored on input.

#include <array>

#include <Eigen/Core>

#include "fem/voxel_grid.hpp"

namespace bemshape::fem {

template <int D>
class ShapeFeatureOperator {
 public:
  /// `reaction`: #cells coefficient c = α(1 − χ) per cell [1]; `a_tilde` = ã = a·h0²
  /// [model units²]; `cell_size` = h [model units].
  ShapeFeatureOperator(const std::array<GridIndex, D>& cells, double cell_size, double a_tilde,
                       Eigen::VectorXd reaction);

  const std::array<GridIndex, D>& cells() const { return cells_; }
  double cell_size() const { return h_; }
  double a_tilde() const { return a_tilde_; }
  const Eigen::VectorXd& reaction() const { return reaction_; }
  GridIndex num_nodes() const { return num_nodes_; }
  /// Number of interior (unknown) nodes Π_d (cells[d] − 1).
  GridIndex num_interior_nodes() const;
  bool is_boundary_node(GridIndex node) const;

  /// y = A·x for every column of x (#nodes×m); boundary rows of y are set to zero.
  void apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& y) const;

  /// The diagonal A_pp (#nodes); 1 on boundary nodes so that it can always be inverted.
  Eigen::VectorXd diagonal() const;

  /// Gershgorin bound max_p Σ_q |A_pq|/A_pp on the spectrum of diag(A)⁻¹A.
  double jacobi_gershgorin_bound() const;

  /// True when every cell count is even and at least 4, i.e. the grid can be halved and the
  /// coarse grid still has an interior node on each axis.
  bool can_coarsen() const;

  /// The same operator rediscretised on the grid with cells twice as large, each coarse cell
  /// taking the mean reaction coefficient of its 2^D children. The ã-term equals the
  /// Galerkin product PᵀAP exactly (nested Q1 spaces, constant ã). The zero-order term is
  /// spectrally equivalent to its Galerkin product with constants independent of h and of
  /// the jump of c: on one cell, ∫_child u² and (1/2^D)∫_cell u² are equivalent norms on Q1
  /// functions. So the hierarchy stays robust where χ jumps inside a coarse cell.
  ShapeFeatureOperator coarsened() const;

 private:
  std::array<GridIndex, D> cells_;
  double h_;
  double a_tilde_;
  Eigen::VectorXd reaction_;
  GridIndex num_nodes_;
  static constexpr int kStencil = D == 2 ? 9 : 27;
  static constexpr int kCorners = 1 << D;
  std::array<double, kStencil> stiffness_stencil_{};  // ã·Σ_cells K_e(o), constant
  std::array<double, kStencil> mass_entry_{};         // M_e(o), one cell
  std::array<double, kStencil> mass_stencil_{};       // Σ_cells M_e(o), all cells alike
  std::array<GridIndex, kStencil> node_offset_{};     // linear offset of node p + o
  std::array<GridIndex, kCorners> cell_offset_{};     // cell p − q relative to cell p − 1
  // For cell corner q (cell p − q) and its node q' (node p + q' − q): stencil index of o.
  std::array<std::array<int, kCorners>, kCorners> cell_node_stencil_{};
};

/// Right-hand sides b_i(p) = ∫ χ ∂φ_p/∂x_i (#nodes×D, zero on boundary nodes) of the
/// weak form for i = 1..D, with χ per cell from the grid.
template <int D>
Eigen::MatrixXd shape_feature_load(const VoxelGrid<D>& grid);

/// The cellwise reaction coefficient c = α(1 − χ) of the grid (#cells).
template <int D>
Eigen::VectorXd reaction_coefficient(const VoxelGrid<D>& grid, double alpha);

extern template class ShapeFeatureOperator<2>;
extern template class ShapeFeatureOperator<3>;

}  // namespace bemshape::fem
