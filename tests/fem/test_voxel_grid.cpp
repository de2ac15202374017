// Grid layout: the margin rule max(h0, 12/κ), multigrid-friendly cell counts, index maps.
#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "fem/voxel_grid.hpp"

using namespace bemshape;
using namespace bemshape::fem;

TEST_CASE("margin is max(h0, 12/kappa)") {
  features::FeatureParameters p;
  p.h0 = 0.3;
  p.a = 0.2;  // 12/κ = 6·a·h0 = 0.36
  CHECK(required_margin(p) == Approx(0.36));
  p.a = 0.1;  // 12/κ = 0.18 < h0
  CHECK(required_margin(p) == Approx(0.3));
}

TEST_CASE("grid covers the box plus the margin and coarsens to a small grid") {
  features::FeatureParameters p;
  p.h0 = 0.3;
  const Eigen::Vector3d lo(-0.5, -0.2, 0.0), hi(0.5, 0.2, 2.0);
  const auto grid = grid_around<3>(lo, hi, 0.01, p, kDefaultMaxCells<3>);
  const double margin = required_margin(p);
  for (int d = 0; d < 3; ++d) {
    CHECK(grid.origin(d) <= lo(d) - margin + 1e-12);
    CHECK(grid.upper_corner()(d) >= hi(d) + margin - 1e-12);
    // Centred on the box.
    CHECK(grid.origin(d) + grid.upper_corner()(d) == Approx(lo(d) + hi(d)).margin(1e-12));
  }
  // Halving while all counts are even reaches a grid of at most 1500 nodes.
  auto cells = grid.cells;
  while (cells[0] % 2 == 0 && cells[1] % 2 == 0 && cells[2] % 2 == 0 &&
         (cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1) > 1500) {
    for (auto& c : cells)
      c /= 2;
  }
  CHECK((cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1) <= 1500);
}

TEST_CASE("grid index maps are inverse to each other") {
  VoxelGrid<3> grid;
  grid.cells = {5, 7, 3};
  grid.cell_size = 0.5;
  for (GridIndex e = 0; e < grid.num_cells(); ++e)
    CHECK(grid.cell_index(grid.cell_multi_index(e)) == e);
  CHECK(grid.node_index({5, 7, 3}) == grid.num_nodes() - 1);
  CHECK(grid.cell_centre({0, 0, 0}).isApprox(Eigen::Vector3d::Constant(0.25)));
}

TEST_CASE("absurd grids are refused before allocating") {
  features::FeatureParameters p;
  p.h0 = 0.3;
  CHECK_THROWS_AS(grid_around<3>(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1e-5, p,
                                 kDefaultMaxCells<3>),
                  ResourceError);
  CHECK_THROWS_AS(grid_around<2>(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), -1.0, p,
                                 kDefaultMaxCells<2>),
                  InputError);
}
