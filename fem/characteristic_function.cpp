#include "fem/characteristic_function.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "geometry/point_inside.hpp"

namespace bemshape::fem {
namespace {

/// For PlannedGrid::cells_with, which only counts: no limit on the size of a grid never
/// allocated.
constexpr GridIndex kUnlimitedCells = std::numeric_limits<GridIndex>::max();

}  // namespace

template <int D>
void fill_characteristic_function(VoxelGrid<D>& grid, const InsideTest<D>& inside,
                                  int samples_per_axis) {
  if (samples_per_axis < 1)
    throw InputError("characteristic function: samples per axis must be at least 1 (got " +
                     std::to_string(samples_per_axis) + ")");
  const GridIndex n = grid.num_cells();
  grid.chi.assign(static_cast<std::size_t>(n), 0.0f);
  int samples = 1;
  for (int d = 0; d < D; ++d)
    samples *= samples_per_axis;
  const double step = grid.cell_size / samples_per_axis;
#pragma omp parallel for schedule(dynamic, 1024)
  for (GridIndex e = 0; e < n; ++e) {
    // A cancelled run skips the remaining cells (an exception cannot leave the loop).
    if (cancellation_requested()) continue;
    const auto c = grid.cell_multi_index(e);
    const Eigen::Matrix<double, D, 1> corner = grid.node_position(c);
    int hits = 0;
    for (int sample = 0; sample < samples; ++sample) {
      Eigen::Matrix<double, D, 1> x = corner;
      int rest = sample;
      for (int d = 0; d < D; ++d) {
        x(d) += (static_cast<double>(rest % samples_per_axis) + 0.5) * step;
        rest /= samples_per_axis;
      }
      hits += inside(x) ? 1 : 0;
    }
    grid.chi[static_cast<std::size_t>(e)] = static_cast<float>(hits) / static_cast<float>(samples);
  }
  throw_if_cancelled();
}

template <int D>
VoxelGrid<D> grid_for_image(const BinaryImage<D>& image, double pixel_size, double cell_size,
                            const features::FeatureParameters& parameters, int samples_per_axis,
                            GridIndex max_cells, const GridCheck<D>& check) {
  if (!(pixel_size > 0.0) || !std::isfinite(pixel_size))
    throw InputError("image: the pixel size must be a positive length (got " +
                     std::to_string(pixel_size) + ")");
  Eigen::Matrix<double, D, 1> lo = Eigen::Matrix<double, D, 1>::Zero(), hi;
  for (int d = 0; d < D; ++d)
    hi(d) = static_cast<double>(image.size[d]) * pixel_size;
  VoxelGrid<D> grid = grid_around<D>(lo, hi, cell_size, parameters, max_cells, true);
  if (check)
    check({grid, [&](double cell, const features::FeatureParameters& p) {
             return grid_around<D>(lo, hi, cell, p, kUnlimitedCells, true).num_cells();
           }});
  const auto size = image.size;
  fill_characteristic_function<D>(
      grid,
      [&](const Eigen::Matrix<double, D, 1>& x) {
        std::array<GridIndex, D> p{};
        for (int d = 0; d < D; ++d) {
          const double u = std::floor(x(d) / pixel_size);
          if (u < 0.0 || u >= static_cast<double>(size[d]))
            return false;
          p[d] = static_cast<GridIndex>(u);
        }
        return image.at(p);
      },
      samples_per_axis);
  return grid;
}

VoxelGrid<3> grid_for_mesh(const geometry::SurfaceMesh& mesh, double cell_size,
                           const features::FeatureParameters& parameters, int samples_per_axis,
                           GridIndex max_cells, const GridCheck<3>& check) {
  if (mesh.empty())
    throw InputError("voxel grid: the surface mesh has no faces");
  const geometry::BoundingBox box = mesh.bounding_box();
  VoxelGrid<3> grid = grid_around<3>(box.min, box.max, cell_size, parameters, max_cells);
  if (check)
    check({grid, [&](double cell, const features::FeatureParameters& p) {
             return grid_around<3>(box.min, box.max, cell, p, kUnlimitedCells).num_cells();
           }});
  const geometry::PointInsideQuery query(mesh);
  fill_characteristic_function<3>(
      grid, [&](const Eigen::Vector3d& x) { return query.inside(x); }, samples_per_axis);
  return grid;
}

template void fill_characteristic_function<2>(VoxelGrid<2>&, const InsideTest<2>&, int);
template void fill_characteristic_function<3>(VoxelGrid<3>&, const InsideTest<3>&, int);
template VoxelGrid<2> grid_for_image<2>(const BinaryImage<2>&, double, double,
                                        const features::FeatureParameters&, int, GridIndex,
                                        const GridCheck<2>&);
template VoxelGrid<3> grid_for_image<3>(const BinaryImage<3>&, double, double,
                                        const features::FeatureParameters&, int, GridIndex,
                                        const GridCheck<3>&);

}  // namespace bemshape::fem
