// bem/hmatrix/hierarchical_matrix.hpp on the Laplace operator [−K0 | V0] of a sphere
// and of a box (flat faces: K0 vanishes between coplanar panels): the product and the
// diagonal blocks agree with the dense matrix of the same entries to the ACA tolerance, and
// the product is bit-identical when repeated.
#include <catch2/catch.hpp>
#include <random>

#include "bem/operators/galerkin_block_generator.hpp"
#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

/// The product and the diagonal blocks against the dense matrix, within `tolerance`
/// (relative) — 10 ε unless the factors are rounded to single precision. Returns the matrix's
/// statistics.
bem::HierarchicalMatrixStats check_against_dense(const geometry::SurfaceMesh& mesh,
                                                 double epsilon, bool single = false,
                                                 double tolerance = 0.0, bool single_near = false,
                                                 bool fixed_point = false) {
  if (tolerance == 0.0) tolerance = 10.0 * epsilon;
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, panels,
                                                                  tree.permutation());
  const bem::HierarchicalMatrix h(tree, generator, {epsilon, 1.0, single, single_near, fixed_point});
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
  CAPTURE(n, epsilon, single, error, h.stats().compression(), h.stats().max_rank);
  CHECK(error < tolerance);

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
    CHECK((blocks[t] - expected).norm() <= tolerance * expected.norm());
  }
  return h.stats();
}

}  // namespace

TEST_CASE("H-matrix of [−K0 | V0] on a sphere: product and diagonal blocks within 10 ε") {
  check_against_dense(geometry::make_geodesic_sphere(1.0, 10), 1e-6);  // 2000 panels
}

TEST_CASE("H-matrix of [−K0 | V0] on a box (zero double layer between coplanar panels)") {
  check_against_dense(geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1.5, 0.3), 0.1),
                      1e-8);
}

TEST_CASE("H-matrix with single-precision factors: half the far-field bytes, error below 1e−6") {
  // Rounding U and V to single precision (unit roundoff 2^−24 ≈ 6e−8) perturbs each low-rank
  // block by about that much relative to its norm; the dense blocks are untouched.
  const auto sphere = geometry::make_geodesic_sphere(1.0, 10);
  const bem::HierarchicalMatrixStats full = check_against_dense(sphere, 1e-8);
  const bem::HierarchicalMatrixStats single = check_against_dense(sphere, 1e-8, true, 1e-6);  // measured 3.6e-7
  CHECK(single.low_rank_entries == full.low_rank_entries);
  CHECK(single.dense_entries == full.dense_entries);
  CHECK(full.low_rank_bytes == 8 * full.low_rank_entries);
  CHECK(single.low_rank_bytes == 4 * single.low_rank_entries);
  CHECK(single.bytes() < full.bytes());

  // The near field in single precision as well: each entry within 6e−8 relative, so the
  // product's error stays at the factors' level; the near-field bytes halve.
  const bem::HierarchicalMatrixStats both = check_against_dense(sphere, 1e-8, true, 1e-6, true);
  CHECK(both.dense_entries == full.dense_entries);
  CHECK(full.dense_bytes == 8 * full.dense_entries);
  CHECK(both.dense_bytes == 4 * both.dense_entries);
  CHECK(both.low_rank_bytes == single.low_rank_bytes);

  // The columns of small singular value in 16- and 8-bit fixed point
  // (bem/hmatrix/adaptive_precision_factors.hpp): their rounding adds at most the
  // leading column's single-precision rounding to each block, so the product stays within
  // the same bound while the factors shrink. Cheaper factors also keep admissible blocks of
  // higher rank low-rank (ACA up to 1.5 times the rank of equal entry counts, kept where the
  // factors take fewer bytes than the dense block): fewer dense blocks, fewer bytes in all.
  const bem::HierarchicalMatrixStats narrow = check_against_dense(sphere, 1e-8, true, 1e-6, true, true);
  CHECK(single.fixed16_columns + single.fixed8_columns == 0);
  CHECK(narrow.fixed16_columns > 0);
  CHECK(narrow.fixed8_columns > 0);
  CHECK(narrow.dense_blocks < both.dense_blocks);
  CHECK(narrow.dense_blocks + narrow.admissible_blocks == both.dense_blocks + both.admissible_blocks);
  CHECK(narrow.dense_entries < both.dense_entries);
  CHECK(narrow.bytes() < both.bytes());
  CHECK(narrow.low_rank_bytes < single.low_rank_bytes * double(narrow.low_rank_entries) /
                                    double(single.low_rank_entries));
}

namespace {

/// A_{o,d}(i, j) = (1 + o + 2d)/(|x_i − y_j| + 0.05) between two point sets (tree order).
class TwoSetKernel final : public bem::OperatorBlockGenerator {
 public:
  TwoSetKernel(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y, const bem::ClusterTree& tx,
               const bem::ClusterTree& ty)
      : x_(x), y_(y), px_(tx.permutation()), py_(ty.permutation()) {}
  int densities() const override { return 2; }
  int outputs() const override { return 3; }
  void fill(Eigen::Index r0, Eigen::Index r1, Eigen::Index c0, Eigen::Index c1,
            Eigen::Ref<Eigen::MatrixXd> out) const override {
    const Eigen::Index m = r1 - r0, n = c1 - c0;
    for (Eigen::Index r = 0; r < m; ++r)
      for (Eigen::Index c = 0; c < n; ++c) {
        const double k = 1.0 / ((x_.row(px_[size_t(r0 + r)]) - y_.row(py_[size_t(c0 + c)])).norm() + 0.05);
        for (int o = 0; o < 3; ++o)
          for (int d = 0; d < 2; ++d) out(o * m + r, d * n + c) = (1 + o + 2 * d) * k;
      }
  }

 private:
  const Eigen::MatrixX3d &x_, &y_;
  const std::vector<Eigen::Index>&px_, &py_;
};

}  // namespace

TEST_CASE("rectangular H-matrix (two trees, three outputs, two densities) = dense product") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::MatrixX3d x(900, 3), y(700, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i) x.row(i) << 2 * u(rng), u(rng), 0.2 * u(rng);
  for (Eigen::Index j = 0; j < y.rows(); ++j) y.row(j) << 2 * u(rng), u(rng), 0.5 + 0.2 * u(rng);
  const bem::ClusterTree tx(x, 24), ty(y, 24);
  const TwoSetKernel kernel(x, y, tx, ty);
  const bem::HierarchicalMatrix h(tx, ty, kernel, {1e-8, 1.0});
  CHECK(h.stats().admissible_blocks > 0);
  CHECK(h.stats().full_entries == 3ull * 900 * 2 * 700);
  Eigen::MatrixXd dense(3 * 900, 2 * 700);
  kernel.fill(0, 900, 0, 700, dense);
  Eigen::MatrixXd v(700, 2);
  for (double& e : v.reshaped()) e = u(rng) - 0.5;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(900, 3);
  h.multiply_add(v, out);
  const Eigen::VectorXd exact = dense * v.reshaped();  // rows o·900 + i
  CHECK((out.reshaped() - exact).norm() < 1e-7 * exact.norm());

  // Three vectors at once (x: 700 × 2·3, y: 900 × 3·3) give each vector's product alone.
  Eigen::MatrixXd v3(700, 6);
  for (double& e : v3.reshaped()) e = u(rng) - 0.5;
  Eigen::MatrixXd out3 = Eigen::MatrixXd::Zero(900, 9);
  h.multiply_add(v3, out3);
  for (int j = 0; j < 3; ++j) {
    Eigen::MatrixXd alone = Eigen::MatrixXd::Zero(900, 3);
    h.multiply_add(v3.middleCols(2 * j, 2), alone);
    CHECK((out3.middleCols(3 * j, 3) - alone).norm() <= 1e-14 * alone.norm());
    const Eigen::MatrixXd vj = v3.middleCols(2 * j, 2);
    const Eigen::VectorXd exact_j = dense * vj.reshaped();
    const Eigen::MatrixXd outj = out3.middleCols(3 * j, 3);
    CHECK((outj.reshaped() - exact_j).norm() < 1e-7 * exact_j.norm());
  }
}

namespace {

/// A(i, j) = 1 on the diagonal blocks' diagonal, 0 elsewhere: every admissible block is
/// zero, so the cross approximation returns rank 0 for all of them.
class DiagonalKernel final : public bem::OperatorBlockGenerator {
 public:
  int densities() const override { return 1; }
  void fill(Eigen::Index r0, Eigen::Index r1, Eigen::Index c0, Eigen::Index c1,
            Eigen::Ref<Eigen::MatrixXd> out) const override {
    for (Eigen::Index r = r0; r < r1; ++r)
      for (Eigen::Index c = c0; c < c1; ++c) out(r - r0, c - c0) = r == c ? 1.0 : 0.0;
  }
};

}  // namespace

TEST_CASE("H-matrix with rank-0 blocks, in double and single precision: the identity") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::MatrixX3d points(600, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) << u(rng), u(rng), u(rng);
  const bem::ClusterTree tree(points, 16);
  for (const bool single : {false, true}) {
    CAPTURE(single);
    const bem::HierarchicalMatrix h(tree, DiagonalKernel{}, {1e-8, 2.0, single});
    REQUIRE(h.stats().admissible_blocks > 0);
    CHECK(h.stats().low_rank_entries == 0);
    CHECK(h.stats().low_rank_bytes == 0);
    CHECK(h.stats().max_rank == 0);
    Eigen::VectorXd x(600);
    for (double& e : x) e = u(rng);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(600);
    h.multiply_add(x, y);
    CHECK(y == x);
    const auto blocks = h.diagonal_blocks({{0, 300}, {300, 600}});
    for (const Eigen::MatrixXd& b : blocks) CHECK(b == Eigen::MatrixXd::Identity(300, 300));
  }
}
