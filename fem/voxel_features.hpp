#pragma once
// Shape features per cell of a voxel solution, computed by the functions the boundary
// element path uses (features/point_features.hpp), so both report the same quantities.
//
// s and ∇s are evaluated at cell centres from the Q1 nodal values (q1_element.hpp): the
// centre value is the mean of the 2^D corner values, the centre gradient the difference
// quotient of opposite faces, which is second-order accurate on a uniform grid. A cell is
// inside the solid (χ = 1 for the features) when its χ ≥ 1/2.

#include <Eigen/Core>

#include "features/feature_parameters.hpp"
#include "features/point_features.hpp"
#include "fem/voxel_grid.hpp"

namespace bemshape::fem {

/// A cell counts as solid for the feature functions when χ ≥ this (majority of its volume).
inline constexpr float kSolidFraction = 0.5f;

template <int D>
struct VoxelFeatures {
  Eigen::MatrixXd s;                ///< #cells×D s at cell centres [model units]
  features::FeatureField<D> field;  ///< #cells rows each (see point_features.hpp)
};

/// s and ∇s at every cell centre: s_cells #cells×D, grad_cells #cells×D² with ∂s_i/∂x_j at
/// column i·D + j. `s_nodes`: #nodes×D.
template <int D>
void cell_centre_values(const VoxelGrid<D>& grid, const Eigen::MatrixXd& s_nodes,
                        Eigen::MatrixXd& s_cells, Eigen::MatrixXd& grad_cells);

/// Features of every cell. A parameters.skeleton_width of 0 is replaced by the cell size
/// (the paper's suggestion for w: "e.g. the pixel size").
template <int D>
VoxelFeatures<D> voxel_features(const VoxelGrid<D>& grid, const Eigen::MatrixXd& s_nodes,
                                features::FeatureParameters parameters);

extern template VoxelFeatures<2> voxel_features<2>(const VoxelGrid<2>&, const Eigen::MatrixXd&,
                                                   features::FeatureParameters);
extern template VoxelFeatures<3> voxel_features<3>(const VoxelGrid<3>&, const Eigen::MatrixXd&,
                                                   features::FeatureParameters);

}  // namespace bemshape::fem
