// Multigrid: transfer operators are transposes, the coarse operator is the Galerkin
// product where the coefficient is uniform, the V-cycle is symmetric (a valid CG
// preconditioner), and CG iteration counts stay flat as the grid is refined.
#include <catch2/catch.hpp>

#include "fem/characteristic_function.hpp"
#include "linalg/conjugate_gradient.hpp"
#include "fem/multigrid.hpp"

using namespace bemshape;
using namespace bemshape::fem;

namespace {

template <int D>
Eigen::MatrixXd random_interior(const ShapeFeatureOperator<D>& op, int columns) {
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(op.num_nodes(), columns);
  for (GridIndex i = 0; i < op.num_nodes(); ++i)
    if (op.is_boundary_node(i))
      x.row(i).setZero();
  return x;
}

/// The paper's bars on a unit-size layout: three bars of different widths, 2-D grid of n².
VoxelGrid<2> bars_grid(GridIndex n) {
  VoxelGrid<2> grid;
  grid.cells = {n, n};
  grid.cell_size = 2.0 / static_cast<double>(n);
  grid.origin = Eigen::Vector2d(-1.0, -1.0);
  fill_characteristic_function<2>(grid, [](const Eigen::Vector2d& x) {
    const bool rows = std::abs(x.y()) < 0.6;
    return rows && ((x.x() > -0.7 && x.x() < -0.5) || (x.x() > -0.2 && x.x() < 0.1) ||
                    (x.x() > 0.3 && x.x() < 0.7) || x.squaredNorm() > 0.85 * 0.85 * 1.4);
  });
  return grid;
}

}  // namespace

TEST_CASE("restriction is the transpose of prolongation") {
  const std::array<GridIndex, 3> fine_cells{8, 4, 6};
  ShapeFeatureOperator<3> fine(fine_cells, 0.1, 1.0, Eigen::VectorXd::Zero(8 * 4 * 6));
  const auto coarse = fine.coarsened();
  const Eigen::MatrixXd xc = random_interior<3>(coarse, 1), xf = random_interior<3>(fine, 1);
  Eigen::MatrixXd pxc = Eigen::MatrixXd::Zero(fine.num_nodes(), 1), rxf;
  prolongate_add<3>(fine_cells, xc, pxc);
  restrict_transpose<3>(fine_cells, xf, rxf);
  CHECK(xf.col(0).dot(pxc.col(0)) == Approx(xc.col(0).dot(rxf.col(0))).epsilon(1e-12));
}

TEST_CASE("prolongation reproduces linear functions") {
  const std::array<GridIndex, 2> fine_cells{8, 8};
  ShapeFeatureOperator<2> fine(fine_cells, 0.1, 1.0, Eigen::VectorXd::Zero(64));
  const auto coarse = fine.coarsened();
  Eigen::MatrixXd xc(coarse.num_nodes(), 1), xf = Eigen::MatrixXd::Zero(fine.num_nodes(), 1);
  for (GridIndex j = 0; j <= 4; ++j)
    for (GridIndex i = 0; i <= 4; ++i)
      xc(j * 5 + i, 0) = 1.0 + 2.0 * i - 3.0 * j;
  prolongate_add<2>(fine_cells, xc, xf);
  for (GridIndex j = 1; j < 8; ++j)
    for (GridIndex i = 1; i < 8; ++i)
      CHECK(xf(j * 9 + i, 0) == Approx(1.0 + 1.0 * i - 1.5 * j));
}

TEST_CASE("coarse operator is the Galerkin product PᵀAP for a uniform coefficient") {
  const std::array<GridIndex, 2> fine_cells{8, 8};
  ShapeFeatureOperator<2> fine(fine_cells, 0.1, 0.018, Eigen::VectorXd::Constant(64, 20.0));
  const auto coarse = fine.coarsened();
  const Eigen::MatrixXd xc = random_interior<2>(coarse, 1);
  Eigen::MatrixXd yc, xf = Eigen::MatrixXd::Zero(fine.num_nodes(), 1), yf, galerkin;
  coarse.apply(xc, yc);
  prolongate_add<2>(fine_cells, xc, xf);
  fine.apply(xf, yf);
  restrict_transpose<2>(fine_cells, yf, galerkin);
  CHECK((galerkin - yc).norm() <= 1e-12 * yc.norm());
}

TEST_CASE("one V-cycle is a symmetric positive definite map") {
  const auto grid = bars_grid(128);
  Multigrid<2> mg(ShapeFeatureOperator<2>(grid.cells, grid.cell_size, 0.018,
                                          reaction_coefficient<2>(grid, 20.0)));
  REQUIRE(mg.num_levels() >= 3);
  const Eigen::MatrixXd x = random_interior<2>(mg.fine_operator(), 2);
  Eigen::MatrixXd z;
  mg.apply(x, z);
  const double xz = x.col(0).dot(z.col(1)), zx = x.col(1).dot(z.col(0));
  CHECK(xz == Approx(zx).epsilon(1e-10));
  CHECK(x.col(0).dot(z.col(0)) > 0.0);
}

TEST_CASE("CG iteration counts do not grow with the grid (2-D, 32² to 256²)") {
  // Multigrid-preconditioned CG converges in a number of iterations independent of h; the
  // bound 1.5× between the coarsest and the finest grid leaves room for pre-asymptotic
  // wobble while catching a hierarchy whose convergence degrades like h^{−1/2} (×2.8).
  constexpr double kGrowthBound = 1.5;
  // Coarsen every grid down to 4 × 4 cells, so even 32² runs a real V-cycle.
  MultigridOptions options;
  options.max_coarse_nodes = 25;
  std::vector<int> iterations;
  for (GridIndex n : {32, 64, 128, 256}) {
    const auto grid = bars_grid(n);
    Multigrid<2> mg(ShapeFeatureOperator<2>(grid.cells, grid.cell_size, 0.018,
                                            reaction_coefficient<2>(grid, 20.0)),
                    options);
    const Eigen::MatrixXd b = shape_feature_load<2>(grid);
    Eigen::MatrixXd x;
    const auto report = linalg::conjugate_gradient(mg.fine_operator(), mg, b, x, 1e-8, 100);
    REQUIRE(report.converged);
    iterations.push_back(report.iterations);
    // Independent check of the residual the report claims.
    Eigen::MatrixXd ax;
    mg.fine_operator().apply(x, ax);
    CHECK((b - ax).norm() <= 1.01e-8 * std::sqrt(2.0) * b.norm());
  }
  INFO("iterations 32², 64², 128², 256²: " << iterations[0] << ", " << iterations[1] << ", "
                                           << iterations[2] << ", " << iterations[3]);
  CHECK(iterations.back() <= kGrowthBound * iterations.front());
  CHECK(*std::max_element(iterations.begin(), iterations.end()) <= 20);
}

TEST_CASE("CG iteration counts do not grow with the grid (3-D, 16³ to 64³)") {
  constexpr double kGrowthBound = 1.5;
  MultigridOptions options;
  options.max_coarse_nodes = 125;
  std::vector<int> iterations;
  for (GridIndex n : {16, 32, 64}) {
    VoxelGrid<3> grid;
    grid.cells = {n, n, n};
    grid.cell_size = 2.0 / static_cast<double>(n);
    grid.origin = Eigen::Vector3d::Constant(-1.0);
    fill_characteristic_function<3>(
        grid, [](const Eigen::Vector3d& x) { return x.norm() < 0.6 && x.norm() > 0.3; });
    Multigrid<3> mg(ShapeFeatureOperator<3>(grid.cells, grid.cell_size, 0.018,
                                            reaction_coefficient<3>(grid, 20.0)),
                    options);
    Eigen::MatrixXd x;
    const auto report =
        linalg::conjugate_gradient(mg.fine_operator(), mg, shape_feature_load<3>(grid), x, 1e-8, 100);
    REQUIRE(report.converged);
    iterations.push_back(report.iterations);
  }
  INFO("iterations 16³, 32³, 64³: " << iterations[0] << ", " << iterations[1] << ", "
                                    << iterations[2]);
  CHECK(iterations.back() <= kGrowthBound * iterations.front());
}
