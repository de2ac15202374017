#include "fem/voxel_features.hpp"

#include <vector>

#include "core/assert.hpp"
#include "fem/q1_element.hpp"

namespace bemshape::fem {

template <int D>
void cell_centre_values(const VoxelGrid<D>& grid, const Eigen::MatrixXd& s_nodes,
                        Eigen::MatrixXd& s_cells, Eigen::MatrixXd& grad_cells) {
  BEMSHAPE_ASSERT(s_nodes.rows() == grid.num_nodes() && s_nodes.cols() == D,
                  "s has one row per node and one column per component");
  constexpr int kCorners = 1 << D;
  const GridIndex n = grid.num_cells();
  s_cells.resize(n, D);
  grad_cells.resize(n, D * D);
  std::array<GridIndex, kCorners> corner_offset{};
  std::array<std::array<double, D>, kCorners> weight{};
  for (int q = 0; q < kCorners; ++q) {
    const auto corner = corner_of<D>(q);
    GridIndex stride = 1;
    for (int d = 0; d < D; ++d) {
      corner_offset[q] += corner[d] * stride;
      stride *= grid.cells[d] + 1;
      weight[q][d] = q1_centre_gradient_weight<D>(corner, d, grid.cell_size);
    }
  }
  const double mean = 1.0 / kCorners;
#pragma omp parallel for schedule(static)
  for (GridIndex e = 0; e < n; ++e) {
    const GridIndex base = grid.node_index(grid.cell_multi_index(e));
    for (int i = 0; i < D; ++i) {
      double value = 0.0;
      std::array<double, D> gradient{};
      for (int q = 0; q < kCorners; ++q) {
        const double v = s_nodes(base + corner_offset[q], i);
        value += v;
        for (int j = 0; j < D; ++j)
          gradient[j] += weight[q][j] * v;
      }
      s_cells(e, i) = mean * value;
      for (int j = 0; j < D; ++j)
        grad_cells(e, i * D + j) = gradient[j];
    }
  }
}

template <int D>
VoxelFeatures<D> voxel_features(const VoxelGrid<D>& grid, const Eigen::MatrixXd& s_nodes,
                                features::FeatureParameters parameters) {
  if (parameters.skeleton_width == 0.0)
    parameters.skeleton_width = grid.cell_size;
  VoxelFeatures<D> result;
  Eigen::MatrixXd gradient;
  cell_centre_values<D>(grid, s_nodes, result.s, gradient);
  std::vector<char> inside(static_cast<std::size_t>(grid.num_cells()));
  for (std::size_t e = 0; e < inside.size(); ++e)
    inside[e] = grid.chi[e] >= kSolidFraction;
  result.field = features::compute_features<D>(result.s, gradient, inside, parameters);
  return result;
}

template void cell_centre_values<2>(const VoxelGrid<2>&, const Eigen::MatrixXd&, Eigen::MatrixXd&,
                                    Eigen::MatrixXd&);
template void cell_centre_values<3>(const VoxelGrid<3>&, const Eigen::MatrixXd&, Eigen::MatrixXd&,
                                    Eigen::MatrixXd&);
template VoxelFeatures<2> voxel_features<2>(const VoxelGrid<2>&, const Eigen::MatrixXd&,
                                            features::FeatureParameters);
template VoxelFeatures<3> voxel_features<3>(const VoxelGrid<3>&, const Eigen::MatrixXd&,
                                            features::FeatureParameters);

}  // namespace bemshape::fem
