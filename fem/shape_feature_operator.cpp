#include "fem/shape_feature_operator.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/assert.hpp"
#include "fem/q1_element.hpp"

namespace bemshape::fem {
namespace {

/// Stencil index Σ_d (o_d + 1)·3^d of an offset o ∈ {−1, 0, 1}^D.
template <int D>
int stencil_index(const std::array<int, D>& o) {
  int index = 0;
  for (int d = D - 1; d >= 0; --d)
    index = 3 * index + (o[d] + 1);
  return index;
}

template <int D>
std::array<int, D> stencil_offset(int index) {
  std::array<int, D> o{};
  for (int d = 0; d < D; ++d) {
    o[d] = index % 3 - 1;
    index /= 3;
  }
  return o;
}

/// Interior nodes are visited line by line along x: line ℓ enumerates (p_1, …, p_{D−1}).
template <int D>
GridIndex interior_lines(const std::array<GridIndex, D>& cells) {
  GridIndex n = 1;
  for (int d = 1; d < D; ++d)
    n *= cells[d] - 1;
  return n;
}

/// Linear index of node (1, p_1, …) of interior line ℓ, and of cell (0, p_1 − 1, …).
template <int D>
std::pair<GridIndex, GridIndex> line_start(const std::array<GridIndex, D>& cells, GridIndex line) {
  GridIndex node = 0, cell = 0, node_stride = cells[0] + 1, cell_stride = cells[0];
  node += 1;
  for (int d = 1; d < D; ++d) {
    const GridIndex p = line % (cells[d] - 1) + 1;
    line /= cells[d] - 1;
    node += p * node_stride;
    cell += (p - 1) * cell_stride;
    node_stride *= cells[d] + 1;
    cell_stride *= cells[d];
  }
  return {node, cell};
}

}  // namespace

template <int D>
ShapeFeatureOperator<D>::ShapeFeatureOperator(const std::array<GridIndex, D>& cells,
                                              double cell_size, double a_tilde,
                                              Eigen::VectorXd reaction)
    : cells_(cells), h_(cell_size), a_tilde_(a_tilde), reaction_(std::move(reaction)) {
  num_nodes_ = 1;
  GridIndex num_cells = 1;
  for (int d = 0; d < D; ++d) {
    BEMSHAPE_ASSERT(cells_[d] >= 2, "a grid needs two cells per axis for an interior node");
    num_nodes_ *= cells_[d] + 1;
    num_cells *= cells_[d];
  }
  BEMSHAPE_ASSERT(reaction_.size() == num_cells, "one reaction coefficient per cell");

  std::array<GridIndex, D> node_stride{}, cell_stride{};
  node_stride[0] = cell_stride[0] = 1;
  for (int d = 1; d < D; ++d) {
    node_stride[d] = node_stride[d - 1] * (cells_[d - 1] + 1);
    cell_stride[d] = cell_stride[d - 1] * cells_[d - 1];
  }
  for (int s = 0; s < kStencil; ++s) {
    const auto o = stencil_offset<D>(s);
    int zeros = 0;
    node_offset_[s] = 0;
    for (int d = 0; d < D; ++d) {
      zeros += o[d] == 0;
      node_offset_[s] += o[d] * node_stride[d];
    }
    // A pair of nodes at offset o shares 2^{#zero components} cells.
    stiffness_stencil_[s] = a_tilde_ * static_cast<double>(1 << zeros) * q1_stiffness<D>(o, h_);
    mass_entry_[s] = q1_mass<D>(o, h_);
    mass_stencil_[s] = static_cast<double>(1 << zeros) * mass_entry_[s];
  }
  for (int q = 0; q < kCorners; ++q) {
    const auto corner = corner_of<D>(q);
    cell_offset_[q] = 0;
    for (int d = 0; d < D; ++d)
      cell_offset_[q] += (1 - corner[d]) * cell_stride[d];
    for (int r = 0; r < kCorners; ++r) {
      const auto other = corner_of<D>(r);
      std::array<int, D> o{};
      for (int d = 0; d < D; ++d)
        o[d] = other[d] - corner[d];
      cell_node_stencil_[q][r] = stencil_index<D>(o);
    }
  }
}

template <int D>
GridIndex ShapeFeatureOperator<D>::num_interior_nodes() const {
  GridIndex n = 1;
  for (int d = 0; d < D; ++d)
    n *= cells_[d] - 1;
  return n;
}

template <int D>
bool ShapeFeatureOperator<D>::is_boundary_node(GridIndex node) const {
  for (int d = 0; d < D; ++d) {
    const GridIndex p = node % (cells_[d] + 1);
    node /= cells_[d] + 1;
    if (p == 0 || p == cells_[d])
      return true;
  }
  return false;
}

template <int D>
void ShapeFeatureOperator<D>::apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& y) const {
  BEMSHAPE_ASSERT(x.rows() == num_nodes_, "operator input has one row per node");
  const Eigen::Index m = x.cols();
  y.setZero(num_nodes_, m);
  const GridIndex lines = interior_lines<D>(cells_);
  const GridIndex run = cells_[0] - 1;
  const double* c = reaction_.data();
  const double* xd = x.data();
  double* yd = y.data();
  const GridIndex column = num_nodes_;
#pragma omp parallel
  {
    // The stencils of one line of nodes, stored entry-major so that the products below
    // stream along x (contiguous in memory, vectorised) instead of gathering 3^D rows per node.
    std::vector<double> line_stencil(static_cast<std::size_t>(kStencil * run));
#pragma omp for schedule(static)
    for (GridIndex line = 0; line < lines; ++line) {
      const auto [node0, cell0] = line_start<D>(cells_, line);
      for (GridIndex k = 0; k < run; ++k) {
        const GridIndex cell = cell0 + k;
        const double c0 = c[cell + cell_offset_[0]];
        bool uniform = true;
        for (int q = 1; q < kCorners; ++q)
          uniform = uniform && c[cell + cell_offset_[q]] == c0;
        if (uniform) {
          // Away from the surface all 2^D cells agree (solid or void): one constant stencil.
          for (int s = 0; s < kStencil; ++s)
            line_stencil[s * run + k] = stiffness_stencil_[s] + c0 * mass_stencil_[s];
        } else {
          for (int s = 0; s < kStencil; ++s)
            line_stencil[s * run + k] = stiffness_stencil_[s];
          for (int q = 0; q < kCorners; ++q) {
            const double cq = c[cell + cell_offset_[q]];
            if (cq == 0.0)
              continue;
            for (int r = 0; r < kCorners; ++r) {
              const int s = cell_node_stencil_[q][r];
              line_stencil[s * run + k] += cq * mass_entry_[s];
            }
          }
        }
      }
      for (Eigen::Index j = 0; j < m; ++j) {
        double* __restrict out = yd + j * column + node0;
        for (int s = 0; s < kStencil; ++s) {
          const double* __restrict in = xd + j * column + node0 + node_offset_[s];
          const double* __restrict a = line_stencil.data() + s * run;
          for (GridIndex k = 0; k < run; ++k)
            out[k] += a[k] * in[k];
        }
      }
    }
  }
}

template <int D>
Eigen::VectorXd ShapeFeatureOperator<D>::diagonal() const {
  Eigen::VectorXd diag = Eigen::VectorXd::Ones(num_nodes_);
  const GridIndex lines = interior_lines<D>(cells_);
  const GridIndex run = cells_[0] - 1;
  const int centre = kStencil / 2;
#pragma omp parallel for schedule(static)
  for (GridIndex line = 0; line < lines; ++line) {
    const auto [node0, cell0] = line_start<D>(cells_, line);
    for (GridIndex k = 0; k < run; ++k) {
      double c_sum = 0.0;
      for (int q = 0; q < kCorners; ++q)
        c_sum += reaction_[cell0 + k + cell_offset_[q]];
      diag[node0 + k] = stiffness_stencil_[centre] + c_sum * mass_entry_[centre];
    }
  }
  return diag;
}

template <int D>
double ShapeFeatureOperator<D>::jacobi_gershgorin_bound() const {
  const GridIndex lines = interior_lines<D>(cells_);
  const GridIndex run = cells_[0] - 1;
  const int centre = kStencil / 2;
  double bound = 0.0;
#pragma omp parallel for schedule(static) reduction(max : bound)
  for (GridIndex line = 0; line < lines; ++line) {
    const auto [node0, cell0] = line_start<D>(cells_, line);
    for (GridIndex k = 0; k < run; ++k) {
      std::array<double, kStencil> stencil = stiffness_stencil_;
      for (int q = 0; q < kCorners; ++q) {
        const double cq = reaction_[cell0 + k + cell_offset_[q]];
        for (int r = 0; r < kCorners; ++r) {
          const int s = cell_node_stencil_[q][r];
          stencil[s] += cq * mass_entry_[s];
        }
      }
      double row = 0.0;
      for (int s = 0; s < kStencil; ++s)
        row += std::abs(stencil[s]);
      bound = std::max(bound, row / stencil[centre]);
    }
  }
  return bound;
}

template <int D>
bool ShapeFeatureOperator<D>::can_coarsen() const {
  for (int d = 0; d < D; ++d)
    if (cells_[d] % 2 != 0 || cells_[d] < 4)
      return false;
  return true;
}

template <int D>
ShapeFeatureOperator<D> ShapeFeatureOperator<D>::coarsened() const {
  BEMSHAPE_ASSERT(can_coarsen(), "coarsening needs even cell counts of at least 4");
  std::array<GridIndex, D> coarse{};
  GridIndex num_coarse = 1;
  for (int d = 0; d < D; ++d) {
    coarse[d] = cells_[d] / 2;
    num_coarse *= coarse[d];
  }
  Eigen::VectorXd reaction(num_coarse);
  const double weight = 1.0 / kCorners;
#pragma omp parallel for schedule(static)
  for (GridIndex index = 0; index < num_coarse; ++index) {
    GridIndex rest = index, fine_base = 0, stride = 1;
    std::array<GridIndex, D> fine_stride{};
    for (int d = 0; d < D; ++d) {
      const GridIndex c = rest % coarse[d];
      rest /= coarse[d];
      fine_base += 2 * c * stride;
      fine_stride[d] = stride;
      stride *= cells_[d];
    }
    double sum = 0.0;
    for (int q = 0; q < kCorners; ++q) {
      GridIndex fine = fine_base;
      for (int d = 0; d < D; ++d)
        fine += ((q >> d) & 1) * fine_stride[d];
      sum += reaction_[fine];
    }
    reaction[index] = weight * sum;
  }
  return ShapeFeatureOperator(coarse, 2.0 * h_, a_tilde_, std::move(reaction));
}

template <int D>
Eigen::MatrixXd shape_feature_load(const VoxelGrid<D>& grid) {
  BEMSHAPE_ASSERT(static_cast<GridIndex>(grid.chi.size()) == grid.num_cells(), "χ not filled");
  Eigen::MatrixXd load = Eigen::MatrixXd::Zero(grid.num_nodes(), D);
  const auto& cells = grid.cells;
  std::array<GridIndex, D> cell_stride{};
  cell_stride[0] = 1;
  for (int d = 1; d < D; ++d)
    cell_stride[d] = cell_stride[d - 1] * cells[d - 1];
  constexpr int kCorners = 1 << D;
  std::array<GridIndex, kCorners> cell_offset{};
  std::array<std::array<double, D>, kCorners> weight{};
  for (int q = 0; q < kCorners; ++q) {
    const auto corner = corner_of<D>(q);
    for (int d = 0; d < D; ++d) {
      cell_offset[q] += (1 - corner[d]) * cell_stride[d];
      weight[q][d] = q1_gradient_integral<D>(corner, d, grid.cell_size);
    }
  }
  const GridIndex lines = interior_lines<D>(cells);
  const GridIndex run = cells[0] - 1;
  const GridIndex column = grid.num_nodes();
  double* b = load.data();
#pragma omp parallel for schedule(static)
  for (GridIndex line = 0; line < lines; ++line) {
    const auto [node0, cell0] = line_start<D>(cells, line);
    for (GridIndex k = 0; k < run; ++k) {
      for (int q = 0; q < kCorners; ++q) {
        const double chi = grid.chi[cell0 + k + cell_offset[q]];
        if (chi == 0.0f)
          continue;
        for (int d = 0; d < D; ++d)
          b[d * column + node0 + k] += chi * weight[q][d];
      }
    }
  }
  return load;
}

template <int D>
Eigen::VectorXd reaction_coefficient(const VoxelGrid<D>& grid, double alpha) {
  BEMSHAPE_ASSERT(static_cast<GridIndex>(grid.chi.size()) == grid.num_cells(), "χ not filled");
  Eigen::VectorXd c(grid.num_cells());
  for (GridIndex e = 0; e < grid.num_cells(); ++e)
    c[e] = alpha * (1.0 - static_cast<double>(grid.chi[e]));
  return c;
}

template class ShapeFeatureOperator<2>;
template class ShapeFeatureOperator<3>;
template Eigen::MatrixXd shape_feature_load<2>(const VoxelGrid<2>&);
template Eigen::MatrixXd shape_feature_load<3>(const VoxelGrid<3>&);
template Eigen::VectorXd reaction_coefficient<2>(const VoxelGrid<2>&, double);
template Eigen::VectorXd reaction_coefficient<3>(const VoxelGrid<3>&, double);

}  // namespace bemshape::fem
