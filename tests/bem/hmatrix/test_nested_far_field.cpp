// bem/hmatrix/nested_far_field.hpp on the Laplace operator [−K0 | V0] of a sphere:
// every admissible block is either left to the caller or held within the tolerances of the
// operator's own entries, the H² product is the sum of the blocks' products, and the far
// field agrees with the H-matrix's.
#include <catch2/catch.hpp>
#include <random>
#include <set>
#include <utility>

#include "bem/operators/galerkin_block_generator.hpp"
#include "bem/hmatrix/nested_far_field.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

/// The Laplace row of a sphere of 20·frequency² panels on leaves of 16 panels.
struct Operator {
  std::vector<bem::Panel> panels;
  bem::ClusterTree tree;
  bem::BlockPartition partition;
};

Operator laplace_operator(int frequency) {
  const auto mesh = geometry::make_geodesic_sphere(0.5, frequency);
  auto panels = bem::make_panels(mesh);
  bem::ClusterTree tree(panels, 16);
  bem::BlockPartition partition = bem::partition_blocks(tree);
  return {std::move(panels), std::move(tree), std::move(partition)};
}

Eigen::MatrixXd random_densities(Eigen::Index n, Eigen::Index columns, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd x(n, columns);
  for (double& e : x.reshaped())
    e = normal(rng);
  return x;
}

}  // namespace

TEST_CASE("nested far field: every block within the tolerances of the operator's entries",
          "[nested_far_field]") {
  const Operator op = laplace_operator(12);  // 2880 panels
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, op.panels,
                                                                  op.tree.permutation());
  REQUIRE(op.partition.admissible.size() > 100);
  for (const double basis_tolerance : {1e-8, 1e-5}) {
    bem::NestedFarFieldOptions options;
    options.aca_tolerance = 1e-8;
    options.basis_tolerance = basis_tolerance;
    const bem::NestedFarField h2(op.tree, op.partition.admissible, generator, options);
    // Each admissible block is in exactly one of the two lists.
    std::set<std::pair<int, int>> seen;
    for (const auto* list : {&h2.blocks(), &h2.uncompressed()})
      for (const bem::BlockIndex& b : *list)
        CHECK(seen.emplace(b.rows, b.cols).second);
    CHECK(seen.size() == op.partition.admissible.size());
    // Leaves of 16 panels: many of the smallest blocks reach the rank limit (the H-matrix
    // stores them densely too); a third or more are held.
    REQUIRE(h2.blocks().size() > op.partition.admissible.size() / 3);

    double worst = 0.0;
    for (std::size_t b = 0; b < h2.blocks().size(); ++b) {
      const bem::Cluster& t = op.tree.cluster(h2.blocks()[b].rows);
      const bem::Cluster& s = op.tree.cluster(h2.blocks()[b].cols);
      Eigen::MatrixXd exact(t.size(), 2 * s.size());
      generator.fill(t.begin, t.end, s.begin, s.end, exact);
      worst = std::max(worst, (exact - h2.block(b)).norm() / exact.norm());
    }
    // ACA's ε, each side's basis tolerance, and the single-precision storage of the bases
    // and couplings: three factors, each rounded to 2^−24 relative, with the rounding of the
    // sums over ranks of tens (measured below 2e−7 at basis tolerance 1e−8).
    const double bound = options.aca_tolerance + 2.0 * basis_tolerance + 5e-7;
    CAPTURE(basis_tolerance, worst, bound, h2.stats().max_row_rank, h2.stats().max_column_rank);
    CHECK(worst <= bound);
    // The bound is not loose by orders of magnitude where the bases decide it.
    if (basis_tolerance > 1e-6)
      CHECK(worst > 1e-2 * basis_tolerance);
  }
}

TEST_CASE("nested far field: the product is the sum of the blocks' products",
          "[nested_far_field]") {
  const Operator op = laplace_operator(10);  // 2000 panels
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, op.panels,
                                                                  op.tree.permutation());
  const bem::NestedFarField h2(op.tree, op.partition.admissible, generator);
  const Eigen::Index n = op.tree.root().size(), vectors = 3;
  const Eigen::MatrixXd x = random_densities(n, 2 * vectors, 11);
  Eigen::MatrixXd direct = Eigen::MatrixXd::Zero(n, vectors);
  double scale = 0.0;
  for (std::size_t b = 0; b < h2.blocks().size(); ++b) {
    const bem::Cluster& t = op.tree.cluster(h2.blocks()[b].rows);
    const bem::Cluster& s = op.tree.cluster(h2.blocks()[b].cols);
    const Eigen::MatrixXd block = h2.block(b);
    const Eigen::MatrixXd local = bem::gather_densities(x, 2, s.begin, s.size());
    direct.middleRows(t.begin, t.size()) += block * local;
    scale += block.norm() * local.norm();
  }
  Eigen::MatrixXd y = Eigen::MatrixXd::Ones(n, vectors);
  h2.multiply_add(x, y);
  y.array() -= 1.0;  // it adds to y
  // The same stored numbers in a different order of double-precision operations.
  const double error = (y - direct).norm();
  CAPTURE(error, scale, direct.norm());
  CHECK(error <= 1e-12 * scale);
  CHECK(direct.norm() > 1e-3 * scale);  // the far field is not empty
}

TEST_CASE("nested far field: with the near field it is the H-matrix's operator",
          "[nested_far_field]") {
  const Operator op = laplace_operator(12);  // 2880 panels
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, op.panels,
                                                                  op.tree.permutation());
  const bem::NestedFarField h2(op.tree, op.partition.admissible, generator);
  // The near field, with the blocks the H² form left out, as an H-matrix of dense blocks.
  bem::BlockPartition near;
  near.dense = op.partition.dense;
  near.dense.insert(near.dense.end(), h2.uncompressed().begin(), h2.uncompressed().end());
  bem::HierarchicalMatrixOptions exact;
  exact.aca_tolerance = 1e-10;
  const bem::HierarchicalMatrix near_field(op.tree, op.tree, near, generator, exact);
  const bem::HierarchicalMatrix reference(op.tree, generator, exact);

  const Eigen::Index n = op.tree.root().size(), vectors = 3;
  const Eigen::MatrixXd x = random_densities(n, 2 * vectors, 5);
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(n, vectors), expected = y;
  near_field.multiply_add(x, y);
  h2.multiply_add(x, y);
  reference.multiply_add(x, expected);
  for (Eigen::Index j = 0; j < vectors; ++j) {
    const double error = (y.col(j) - expected.col(j)).norm() / expected.col(j).norm();
    CAPTURE(j, error);
    // ε = 1e−8 per block and single-precision storage (the H-matrix's single-precision
    // factors perturb a product by about 4e−7, HierarchicalMatrixOptions).
    CHECK(error < 1e-6);
  }
}

TEST_CASE("nested far field: grouped sums are the blocks' sums over groups", "[nested_far_field]") {
  const Operator op = laplace_operator(10);  // 2000 panels
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, op.panels,
                                                                  op.tree.permutation());
  const bem::NestedFarField h2(op.tree, op.partition.admissible, generator);
  const Eigen::Index n = op.tree.root().size();
  // Groups of clusters of up to 100 panels (not aligned with the leaves of 16, so clusters
  // and blocks meet several groups).
  const std::vector<int> coarse = op.tree.clusters_up_to(100);
  std::vector<Eigen::Index> group(static_cast<std::size_t>(n));
  for (std::size_t c = 0; c < coarse.size(); ++c)
    for (Eigen::Index p = op.tree.cluster(coarse[c]).begin; p < op.tree.cluster(coarse[c]).end; ++p)
      group[std::size_t(p)] = Eigen::Index(c);
  const Eigen::Index m = Eigen::Index(coarse.size());
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(m, 2 * m);
  for (std::size_t b = 0; b < h2.blocks().size(); ++b) {
    const bem::Cluster& t = op.tree.cluster(h2.blocks()[b].rows);
    const bem::Cluster& s = op.tree.cluster(h2.blocks()[b].cols);
    const Eigen::MatrixXd block = h2.block(b);
    for (Eigen::Index i = 0; i < t.size(); ++i)
      for (int d = 0; d < 2; ++d)
        for (Eigen::Index j = 0; j < s.size(); ++j)
          expected(group[std::size_t(t.begin + i)], d * m + group[std::size_t(s.begin + j)]) +=
              block(i, d * s.size() + j);
  }
  const Eigen::MatrixXd sums = h2.grouped_sums(group, m);
  CAPTURE(m, (sums - expected).norm(), expected.norm());
  CHECK(expected.norm() > 0.0);
  CHECK((sums - expected).norm() <= 1e-12 * expected.norm());
}
