#pragma once
// The characteristic function χ of the solid on a voxel grid, sampled from an inside test.
//
// With samples_per_axis = k the test is evaluated at the k^D points (c + (j + ½)/k)·h of
// each cell and χ is the fraction inside:
//   k = 1  (default): χ ∈ {0, 1}, the exact inside test of the cell centre. The feature
//          functions carry χ as an indicator and a binary image is exactly this, so the
//          FEM and image inputs agree cell by cell.
//   k > 1: χ ≈ covered volume fraction. The source term ∫χ e_i·∇ξ and the reaction
//          α(1 − χ) then see the surface inside a cell to O(h/k) instead of O(h), which
//          reduces the staircase error on curved or oblique surfaces at k^D times the cost
//          of the inside tests (the solve is unchanged).

#include <functional>

#include <Eigen/Core>

#include "fem/binary_image.hpp"
#include "fem/voxel_grid.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::fem {

template <int D>
using InsideTest = std::function<bool(const Eigen::Matrix<double, D, 1>& x)>;

/// What grid_for_image and grid_for_mesh show a GridCheck before anything per cell is
/// allocated or computed: the planned grid (cell counts, cell size, origin; χ empty) and, to
/// look for parameters that fit, the cell count a grid around the same solid would have with
/// another cell size and parameters (the margin depends on h0 and a).
template <int D>
struct PlannedGrid {
  const VoxelGrid<D>& grid;
  std::function<GridIndex(double cell_size, const features::FeatureParameters& parameters)>
      cells_with;
};

/// May throw to refuse a planned grid (analysis::voxel_grid_memory_check checks the run's
/// memory with it).
template <int D>
using GridCheck = std::function<void(const PlannedGrid<D>& planned)>;

/// Fills grid.chi from `inside` (called concurrently from several threads: it must be
/// thread-safe). Throws InputError if samples_per_axis < 1.
template <int D>
void fill_characteristic_function(VoxelGrid<D>& grid, const InsideTest<D>& inside,
                                  int samples_per_axis = 1);

/// A grid around an image whose pixels are squares (cubes) of side `pixel_size` [model
/// units], the image occupying [0, size·pixel_size]; χ sampled from the pixel containing
/// each sample point (outside the image: void). Cells need not match pixels. `check`, when
/// set, sees the planned grid first (GridCheck).
template <int D>
VoxelGrid<D> grid_for_image(const BinaryImage<D>& image, double pixel_size, double cell_size,
                            const features::FeatureParameters& parameters, int samples_per_axis = 1,
                            GridIndex max_cells = kDefaultMaxCells<D>,
                            const GridCheck<D>& check = {});

/// A grid around a closed, outward-oriented surface mesh (3-D), χ from the exact inside
/// test of geometry/point_inside.hpp (points on the surface count as outside). Throws
/// InputError if the mesh is not closed (prepare it with geometry's pipeline first).
/// `check`, when set, sees the planned grid first (GridCheck).
VoxelGrid<3> grid_for_mesh(const geometry::SurfaceMesh& mesh, double cell_size,
                           const features::FeatureParameters& parameters, int samples_per_axis = 1,
                           GridIndex max_cells = kDefaultMaxCells<3>,
                           const GridCheck<3>& check = {});

extern template void fill_characteristic_function<2>(VoxelGrid<2>&, const InsideTest<2>&, int);
extern template void fill_characteristic_function<3>(VoxelGrid<3>&, const InsideTest<3>&, int);

}  // namespace bemshape::fem
