// bench/nested_cluster_basis.hpp on the low-rank blocks of the Laplace operator
// [−K0 | V0] of a sphere: the bases are orthonormal and nested, every block is represented
// within the error bound the construction promises, and the ranks fall as the tolerance
// grows.
#include <catch2/catch.hpp>
#include <random>

#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/operators/galerkin_block_generator.hpp"
#include "bench/nested_cluster_basis.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

struct Operator {
  std::vector<bem::Panel> panels;
  bem::ClusterTree tree;
  std::vector<bench::LowRankBlockCopy> blocks;
};

/// The low-rank blocks of the Laplace row of a sphere of 20·frequency² panels as an H-matrix
/// with factors in double precision holds them, at ε = 1e−10, leaves of 16 panels, η = 4 (the
/// solver's).
Operator laplace_operator(int frequency) {
  const auto mesh = geometry::make_geodesic_sphere(0.5, frequency);
  auto panels = bem::make_panels(mesh);
  bem::ClusterTree tree(panels, 16);
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, panels,
                                                                  tree.permutation());
  bem::HierarchicalMatrixOptions options;
  options.aca_tolerance = 1e-10;
  auto blocks =
      bench::far_field_low_rank_blocks(tree, generator, options.aca_tolerance, options.eta);
  return {std::move(panels), std::move(tree), std::move(blocks)};
}

Eigen::Index total_rank(const bench::NestedBasisSide& side) {
  Eigen::Index sum = 0;
  for (const Eigen::Index k : side.rank)
    sum += k;
  return sum;
}

}  // namespace

TEST_CASE("nested cluster bases: orthonormal, nested, every block within 2 tolerance",
          "[nested_cluster_basis]") {
  const Operator op = laplace_operator(12);  // 2880 panels
  REQUIRE(op.blocks.size() > 50);
  for (const double tolerance : {1e-4, 1e-7}) {
    const bench::NestedClusterBasis h2(op.tree, op.blocks, 2, tolerance);
    std::vector<Eigen::MatrixXd> q(op.tree.clusters().size()), p(op.tree.clusters().size());
    for (int c = 0; c < int(op.tree.clusters().size()); ++c) {
      q[std::size_t(c)] = h2.rows().expand(op.tree, c);
      p[std::size_t(c)] = h2.columns().expand(op.tree, c);
      const auto& cl = op.tree.cluster(c);
      REQUIRE(q[std::size_t(c)].rows() == cl.size());
      REQUIRE(p[std::size_t(c)].rows() == 2 * cl.size());
      for (const Eigen::MatrixXd* basis : {&q[std::size_t(c)], &p[std::size_t(c)]}) {
        const Eigen::MatrixXd gram = basis->transpose() * *basis;
        CHECK((gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).norm() < 1e-12);
      }
    }
    double worst = 0.0, worst_direct = 0.0;
    for (std::size_t b = 0; b < op.blocks.size(); ++b) {
      const auto& block = op.blocks[b];
      const Eigen::MatrixXd& qb = q[std::size_t(h2.row_cluster(b))];
      const Eigen::MatrixXd& pb = p[std::size_t(h2.column_cluster(b))];
      worst = std::max(worst, bench::nested_basis_error_bound(block.U, block.V, qb, pb));
      // The coupling matrix is what the bound speaks of: Q S Pᵀ against U Vᵀ directly.
      const Eigen::MatrixXd exact = block.U * block.V.transpose();
      const Eigen::MatrixXd nested = qb * h2.coupling(b) * pb.transpose();
      worst_direct = std::max(worst_direct, (exact - nested).norm() / exact.norm());
    }
    CAPTURE(tolerance, worst, worst_direct, total_rank(h2.rows()), total_rank(h2.columns()));
    CHECK(worst <= 2.0 * tolerance);
    CHECK(worst_direct <= worst * (1.0 + 1e-6) + 1e-13);
    // The bound is not loose by orders of magnitude: the bases drop what they may.
    CHECK(worst_direct > 1e-3 * tolerance);
  }
}

TEST_CASE("nested cluster bases: exact at tolerance 0, ranks fall as the tolerance grows",
          "[nested_cluster_basis]") {
  const Operator op = laplace_operator(10);  // 2000 panels
  const bench::NestedClusterBasis exact(op.tree, op.blocks, 2, 0.0);
  for (std::size_t b = 0; b < op.blocks.size(); ++b) {
    const auto& block = op.blocks[b];
    const Eigen::MatrixXd nested =
        exact.rows().expand(op.tree, exact.row_cluster(b)) * exact.coupling(b) *
        exact.columns().expand(op.tree, exact.column_cluster(b)).transpose();
    const Eigen::MatrixXd direct = block.U * block.V.transpose();
    REQUIRE((direct - nested).norm() <= 1e-12 * direct.norm());
  }
  Eigen::Index previous = total_rank(exact.rows()) + total_rank(exact.columns());
  std::uint64_t previous_entries = exact.storage().entries();
  for (const double tolerance : {1e-10, 1e-7, 1e-4, 1e-2}) {
    const bench::NestedClusterBasis h2(op.tree, op.blocks, 2, tolerance);
    const Eigen::Index ranks = total_rank(h2.rows()) + total_rank(h2.columns());
    CAPTURE(tolerance, ranks, previous);
    CHECK(ranks <= previous);
    CHECK(h2.storage().entries() <= previous_entries);
    previous = ranks;
    previous_entries = h2.storage().entries();
  }
  CHECK(previous < total_rank(exact.rows()) + total_rank(exact.columns()));
}

TEST_CASE("nested cluster bases: the H² product is the blocks' product within the bound",
          "[nested_cluster_basis]") {
  const Operator op = laplace_operator(12);  // 2880 panels
  const Eigen::Index n = op.tree.root().size(), vectors = 3;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd x(n, 2 * vectors);
  for (double& e : x.reshaped())
    e = normal(rng);
  // The far field block by block from the H-matrix's factors, and the bound
  // Σ_b ‖A_b − Q S Pᵀ‖ ‖x|_σ‖ ≤ 2 tolerance Σ_b ‖A_b‖_F ‖x|_σ‖ per vector.
  Eigen::MatrixXd direct = Eigen::MatrixXd::Zero(n, vectors);
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(vectors);
  for (const auto& b : op.blocks) {
    const Eigen::Index m = b.row_end - b.row_begin, s = b.col_end - b.col_begin;
    const Eigen::MatrixXd local = bem::gather_densities(x, 2, b.col_begin, s);
    direct.middleRows(b.row_begin, m) += b.U * (b.V.transpose() * local);
    const double norm = (b.U * b.V.transpose()).norm();
    for (Eigen::Index j = 0; j < vectors; ++j)
      bound(j) += norm * local.col(j).norm();
  }
  for (const double tolerance : {0.0, 1e-8, 1e-5}) {
    const bench::NestedClusterBasis h2(op.tree, op.blocks, 2, tolerance);
    Eigen::MatrixXd y = Eigen::MatrixXd::Ones(n, vectors);
    h2.multiply_add(op.tree, x, y);
    y.array() -= 1.0;  // it adds to y
    for (Eigen::Index j = 0; j < vectors; ++j) {
      const double error = (y.col(j) - direct.col(j)).norm();
      CAPTURE(tolerance, j, error, bound(j), direct.col(j).norm());
      CHECK(error <= 2.0 * tolerance * bound(j) + 1e-12 * bound(j));
      // The bound ignores the cancellation between blocks (random densities: ‖Σ A_b x_b‖ is
      // far below Σ ‖A_b‖‖x_b‖); relative to the product itself the error is still within
      // the per-block 2 tolerance (3.8e−6 at 1e−5 on this sphere).
      CHECK(error <= 2.0 * tolerance * direct.col(j).norm() + 1e-12 * bound(j));
    }
  }
}
