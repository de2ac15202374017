// χ sampling: centre tests give a binary χ whose volume converges to the solid's volume;
// sub-sampling gives fractions whose sum converges faster; images map pixels to cells.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/errors.hpp"
#include "fem/characteristic_function.hpp"

using namespace bemshape;
using namespace bemshape::fem;

TEST_CASE("χ of a disc: binary centre test and area fractions") {
  VoxelGrid<2> grid;
  grid.cells = {64, 64};
  grid.cell_size = 1.0 / 32.0;
  grid.origin = Eigen::Vector2d(-1.0, -1.0);
  const auto disc = [](const Eigen::Vector2d& x) { return x.norm() < 0.7; };
  const double exact = M_PI * 0.49, cell_area = grid.cell_size * grid.cell_size;
  fill_characteristic_function<2>(grid, disc, 1);
  double binary = 0.0;
  for (float c : grid.chi) {
    CHECK((c == 0.0f || c == 1.0f));
    binary += c * cell_area;
  }
  fill_characteristic_function<2>(grid, disc, 8);
  double fraction = 0.0;
  for (float c : grid.chi)
    fraction += c * cell_area;
  // Both within a perimeter strip of the area; the fraction within 1/8 of that.
  const double strip = 2.0 * M_PI * 0.7 * grid.cell_size;
  CHECK(std::abs(binary - exact) < 0.2 * strip);
  CHECK(std::abs(fraction - exact) < 0.2 * strip / 8.0);
  CHECK_THROWS_AS(fill_characteristic_function<2>(grid, disc, 0), InputError);
}

TEST_CASE("image cells: pixels map to cells, grid lines through the image corner") {
  BinaryImage<2> image;
  image.size = {4, 2};
  image.solid = {1, 0, 0, 1, 0, 0, 1, 1};
  features::FeatureParameters p;
  p.h0 = 0.1;
  const double pixel = 0.05;
  // Cells of half a pixel: each pixel becomes 2 × 2 cells.
  const auto grid = grid_for_image<2>(image, pixel, 0.5 * pixel, p);
  double solid_area = 0.0;
  for (GridIndex e = 0; e < grid.num_cells(); ++e) {
    const Eigen::Vector2d x = grid.cell_centre(grid.cell_multi_index(e));
    const auto px = static_cast<GridIndex>(std::floor(x.x() / pixel));
    const auto py = static_cast<GridIndex>(std::floor(x.y() / pixel));
    const bool in_image = x.x() > 0 && x.y() > 0 && px < 4 && py < 2;
    CHECK(grid.chi[e] == (in_image && image.at({px, py}) ? 1.0f : 0.0f));
    solid_area += grid.chi[e] * grid.cell_size * grid.cell_size;
  }
  CHECK(solid_area == Approx(4 * pixel * pixel));
  // Grid lines pass through the image's corner at the origin.
  CHECK(std::abs(std::remainder(grid.origin.x(), grid.cell_size)) < 1e-12);
}
