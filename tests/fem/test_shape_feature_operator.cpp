// The matrix-free operator against a plain element-by-element assembly of the weak form
//   a(s, ξ) = ∫ ã ∇s·∇ξ + ∫ α(1−χ) s ξ,  ℓ_i(ξ) = ∫ χ ∂ξ/∂x_i,
// computed here from 2×2 (2×2×2) Gauss quadrature of the bilinear (trilinear) shape
// functions, independently of q1_element.hpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "fem/shape_feature_operator.hpp"

using namespace bemshape::fem;

namespace {

/// Dense matrix and load by Gauss quadrature, node numbering of voxel_grid.hpp, all nodes.
template <int D>
void assemble_by_quadrature(const VoxelGrid<D>& grid, double a_tilde, double alpha,
                            Eigen::MatrixXd& A, Eigen::MatrixXd& b) {
  const GridIndex n = grid.num_nodes();
  A.setZero(n, n);
  b.setZero(n, D);
  const double h = grid.cell_size, g = 0.5 / std::sqrt(3.0);
  for (GridIndex e = 0; e < grid.num_cells(); ++e) {
    const auto c = grid.cell_multi_index(e);
    const double chi = grid.chi[e];
    for (int qp = 0; qp < (1 << D); ++qp) {
      std::array<double, D> t{};  // local coordinate in [0, 1]
      for (int d = 0; d < D; ++d)
        t[d] = 0.5 + (((qp >> d) & 1) ? g : -g);
      const double weight = std::pow(h, D) / (1 << D);
      std::array<double, 1 << D> phi{};
      std::array<std::array<double, D>, 1 << D> grad{};
      std::array<GridIndex, 1 << D> node{};
      for (int a = 0; a < (1 << D); ++a) {
        std::array<GridIndex, D> p{};
        phi[a] = 1.0;
        for (int d = 0; d < D; ++d) {
          const int bit = (a >> d) & 1;
          p[d] = c[d] + bit;
          phi[a] *= bit ? t[d] : 1.0 - t[d];
        }
        for (int d = 0; d < D; ++d) {
          double v = 1.0;
          for (int k = 0; k < D; ++k) {
            const int bit = (a >> k) & 1;
            v *= k == d ? (bit ? 1.0 / h : -1.0 / h) : (bit ? t[k] : 1.0 - t[k]);
          }
          grad[a][d] = v;
        }
        node[a] = grid.node_index(p);
      }
      for (int a = 0; a < (1 << D); ++a) {
        for (int d = 0; d < D; ++d)
          b(node[a], d) += weight * chi * grad[a][d];
        for (int k = 0; k < (1 << D); ++k) {
          double dot = 0.0;
          for (int d = 0; d < D; ++d)
            dot += grad[a][d] * grad[k][d];
          A(node[a], node[k]) += weight * (a_tilde * dot + alpha * (1.0 - chi) * phi[a] * phi[k]);
        }
      }
    }
  }
}

template <int D>
VoxelGrid<D> random_grid(const std::array<GridIndex, D>& cells, unsigned seed) {
  VoxelGrid<D> grid;
  grid.cells = cells;
  grid.cell_size = 0.13;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (GridIndex e = 0; e < grid.num_cells(); ++e) {
    const double r = u(rng);
    grid.chi.push_back(r < 0.4 ? 0.0f : r < 0.8 ? 1.0f : static_cast<float>(u(rng)));
  }
  return grid;
}

template <int D>
void check_against_quadrature(const std::array<GridIndex, D>& cells) {
  const double a_tilde = 0.018, alpha = 20.0;
  const auto grid = random_grid<D>(cells, 7);
  ShapeFeatureOperator<D> op(grid.cells, grid.cell_size, a_tilde,
                             reaction_coefficient<D>(grid, alpha));
  Eigen::MatrixXd A, b;
  assemble_by_quadrature<D>(grid, a_tilde, alpha, A, b);
  const GridIndex n = grid.num_nodes();
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(n, 3), y;
  for (GridIndex i = 0; i < n; ++i)
    if (op.is_boundary_node(i))
      x.row(i).setZero();
  op.apply(x, y);
  Eigen::MatrixXd expected = A * x;
  for (GridIndex i = 0; i < n; ++i)
    if (op.is_boundary_node(i))
      expected.row(i).setZero();
  CHECK((y - expected).norm() <= 1e-12 * expected.norm());

  const Eigen::MatrixXd load = shape_feature_load<D>(grid);
  for (GridIndex i = 0; i < n; ++i)
    if (op.is_boundary_node(i))
      b.row(i).setZero();
  CHECK((load - b).norm() <= 1e-12 * b.norm());

  const Eigen::VectorXd diag = op.diagonal();
  for (GridIndex i = 0; i < n; ++i)
    if (!op.is_boundary_node(i))
      CHECK(diag[i] == Approx(A(i, i)).epsilon(1e-12));
}

}  // namespace

TEST_CASE("matrix-free 2-D operator and load equal the quadrature assembly") {
  check_against_quadrature<2>({5, 4});
}

TEST_CASE("matrix-free 3-D operator and load equal the quadrature assembly") {
  check_against_quadrature<3>({4, 3, 5});
}

TEST_CASE("operator is symmetric positive definite on interior nodes") {
  const auto grid = random_grid<3>({6, 6, 4}, 3);
  ShapeFeatureOperator<3> op(grid.cells, grid.cell_size, 0.018,
                             reaction_coefficient<3>(grid, 20.0));
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(op.num_nodes(), 2), y;
  for (GridIndex i = 0; i < op.num_nodes(); ++i)
    if (op.is_boundary_node(i))
      x.row(i).setZero();
  op.apply(x, y);
  const double xy = x.col(0).dot(y.col(1)), yx = x.col(1).dot(y.col(0));
  CHECK(xy == Approx(yx).epsilon(1e-12));
  CHECK(x.col(0).dot(y.col(0)) > 0.0);
}
