// bem/hierarchical/hierarchical_matrix.hpp on the Laplace operator [−K0 | V0] of a sphere
// and of a box (flat faces: K0 vanishes between coplanar panels): the product and the
// diagonal blocks agree with the dense matrix of the same entries to the ACA tolerance, and
// the product is bit-identical when repeated.
#include <catch2/catch.hpp>
#include <random>

#include "bem/hierarchical/galerkin_block_generator.hpp"
#include "bem/hierarchical/hierarchical_matrix.hpp"
#include "bem/laplace_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

void check_against_dense(const geometry::SurfaceMesh& mesh, double epsilon) {
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, panels, tree);
  const bem::HierarchicalMatrix h(tree, generator, {epsilon, 1.0});
  const Eigen::Index n = mesh.num_faces();
  Eigen::MatrixXd dense(n, 2 * n);
  generator.fill(0, n, 0, n, dense);

  CHECK(h.stats().admissible_blocks > 0);
  CHECK(h.stats().compression() < 1.0);
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  Eigen::MatrixXd x(n, 2);
  for (double& e : x.reshaped()) e = g(rng);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  h.multiply_add(x, y);
  const Eigen::VectorXd exact = dense.leftCols(n) * x.col(0) + dense.rightCols(n) * x.col(1);
  const double error = (y - exact).norm() / exact.norm();
  CAPTURE(n, epsilon, error, h.stats().compression(), h.stats().max_rank);
  CHECK(error < 10.0 * epsilon);

  Eigen::VectorXd again = Eigen::VectorXd::Zero(n);
  h.multiply_add(x, again);
  CHECK(again == y);

  const auto leaves = tree.clusters_up_to(100);
  std::vector<std::pair<Eigen::Index, Eigen::Index>> ranges;
  for (const int c : leaves) ranges.emplace_back(tree.cluster(c).begin, tree.cluster(c).end);
  const auto blocks = h.diagonal_blocks(ranges);
  for (size_t t = 0; t < ranges.size(); ++t) {
    const auto [b, e] = ranges[t];
    Eigen::MatrixXd expected(e - b, 2 * (e - b));
    expected << dense.block(b, b, e - b, e - b), dense.block(b, n + b, e - b, e - b);
    CHECK((blocks[t] - expected).norm() <= 10.0 * epsilon * expected.norm());
  }
}

}  // namespace

TEST_CASE("H-matrix of [−K0 | V0] on a sphere: product and diagonal blocks within 10 ε") {
  check_against_dense(geometry::make_geodesic_sphere(1.0, 10), 1e-6);  // 2000 panels
}

TEST_CASE("H-matrix of [−K0 | V0] on a box (zero double layer between coplanar panels)") {
  check_against_dense(geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1.5, 0.3), 0.1),
                      1e-8);
}
