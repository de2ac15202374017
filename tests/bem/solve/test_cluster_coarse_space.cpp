// bem/solve/cluster_coarse_space.hpp: the coarse matrix summed from the stored
// operators equals Pᵀ A P computed with products by A, the grouped product A P y equals A
// applied to P y, and the two-level preconditioner is the identity on coarse densities
// (M⁻¹ A P = P).
#include <catch2/catch.hpp>
#include <algorithm>
#include <random>
#include <utility>

#include "bem/solve/cluster_coarse_space.hpp"
#include "bem/operators/galerkin_block_generator.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/kernels/transmission_parameters.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

/// The transmission operator of bem/solve/hmatrix_transmission_solver.hpp on a hollow box, with the
/// Laplace row compressed (single- or double-precision factors) and a small cluster size so
/// the coarse space has a few dozen clusters.
struct System {
  geometry::SurfaceMesh mesh;
  std::vector<bem::Panel> panels;
  bem::ClusterTree tree;
  bem::HierarchicalMatrix laplace;
  bem::YukawaNearField<double> yukawa;
  Eigen::MatrixXd yukawa_dense;  // the same, n × 2n
  Eigen::VectorXd half_mass;

  explicit System(bool single, double tolerance = 1e-8)
      : mesh(geometry::make_hollow_box(Eigen::Vector3d(0.6, 0.5, 0.45), 0.3, 0.1)),
        panels(bem::make_panels(mesh)),
        tree(panels, 16),
        laplace(tree,
                bem::GalerkinBlockGenerator<bem::LaplaceKernel>(bem::LaplaceKernel{}, panels,
                                                                tree.permutation()),
                {tolerance, 2.0, single, single}),
        yukawa(bem::assemble_yukawa_near_field(
            panels, tree, bem::TransmissionParameters::from_shape(0.3, 0.2).kappa)),
        yukawa_dense(yukawa.to_dense()) {
    half_mass.resize(mesh.num_faces());
    for (Eigen::Index p = 0; p < mesh.num_faces(); ++p)
      half_mass(p) = 0.5 * mesh.face_areas()(tree.permutation()[size_t(p)]);
  }

  /// y = A x for the columns of x (2N × k), as the solver applies A.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& x) const {
    const Eigen::Index n = mesh.num_faces();
    Eigen::MatrixXd y(2 * n, x.cols());
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      Eigen::MatrixXd densities(n, 2);
      densities << x.col(j).head(n), x.col(j).tail(n);
      Eigen::VectorXd interior = -half_mass.cwiseProduct(x.col(j).head(n));
      laplace.multiply_add(densities, interior);
      y.col(j).head(n) = interior;
      y.col(j).tail(n) = half_mass.cwiseProduct(x.col(j).head(n)) + yukawa_dense * x.col(j);
    }
    return y;
  }

  /// P (2N × 2m) of the coarse space.
  Eigen::MatrixXd prolongation(const bem::ClusterCoarseSpace& coarse) const {
    const Eigen::Index n = mesh.num_faces(), m = coarse.clusters();
    Eigen::MatrixXd p = Eigen::MatrixXd::Zero(2 * n, 2 * m);
    for (Eigen::Index i = 0; i < n; ++i) {
      p(i, coarse.cluster_of()[size_t(i)]) = 1.0;
      p(n + i, m + coarse.cluster_of()[size_t(i)]) = 1.0;
    }
    return p;
  }
};

constexpr auto kExact = bem::HierarchicalMatrix::GroupedColumns::Storage::exact;

}  // namespace

TEST_CASE("coarse space: A_c summed from the H-matrix and sparse blocks = Pᵀ A P") {
  for (const bool single : {false, true}) {
    const System s(single);
    REQUIRE(s.laplace.stats().admissible_blocks > 0);
    const bem::ClusterCoarseSpace coarse(s.tree, s.laplace, s.yukawa, s.half_mass, 32, kExact);
    const Eigen::Index m = coarse.clusters();
    CAPTURE(single, s.mesh.num_faces(), m);
    REQUIRE(m >= 16);
    // Clusters tile the panels in tree order.
    for (size_t i = 1; i < coarse.cluster_of().size(); ++i)
      REQUIRE(coarse.cluster_of()[i] - coarse.cluster_of()[i - 1] >= 0);
    const Eigen::MatrixXd p = s.prolongation(coarse);
    const Eigen::MatrixXd expected = p.transpose() * s.apply(p);
    const double error = (coarse.matrix() - expected).norm() / expected.norm();
    CAPTURE(error);
    CHECK(error < 1e-13);
  }
}

TEST_CASE("coarse space: A P y from the grouped operators, and M⁻¹ A P y = P y") {
  // Clusters of 32: every block keeps A E. Clusters of 4 (the tree's leaves) and ranks of a
  // 1e−4 tolerance: the largest blocks meet more clusters than their rank and keep U with EᵀV.
  for (const auto& [single, cluster] : {std::pair{false, 32}, std::pair{true, 32}, std::pair{true, 4}}) {
    const System s(single, cluster == 4 ? 1e-4 : 1e-8);
    const bem::ClusterCoarseSpace coarse(s.tree, s.laplace, s.yukawa, s.half_mass, cluster, kExact);
    const Eigen::Index n = s.mesh.num_faces(), m = coarse.clusters();
    CAPTURE(single, cluster, n, m);
    const auto columns = s.laplace.group_columns(coarse.cluster_of(), m, kExact);
    const auto factored = std::count_if(columns.parts.begin(), columns.parts.end(),
                                        [](const auto& p) { return !p.expanded; });
    CHECK((factored > 0) == (cluster == 4));
    std::mt19937 rng(7);
    std::normal_distribution<double> g;
    Eigen::MatrixXd y(2 * m, 3);
    for (double& e : y.reshaped()) e = g(rng);
    const Eigen::MatrixXd p = s.prolongation(coarse);
    const Eigen::MatrixXd expected = s.apply(p * y);
    const Eigen::MatrixXd grouped = coarse.apply_operator(y);
    CHECK((grouped - expected).norm() <= 1e-13 * expected.norm());

    // On r = A P y the coarse solve recovers y, the blocks see a zero residual (to rounding).
    const bem::ClusterBlockPreconditioner blocks(s.tree, s.laplace, s.yukawa, s.half_mass, 64);
    Eigen::MatrixXd z;
    coarse.apply_two_level(blocks, expected, z);
    CHECK((z - p * y).norm() <= 1e-9 * (p * y).norm());
    // Any other residual: z = P A_c⁻¹ Pᵀ r + B (r − A P A_c⁻¹ Pᵀ r).
    Eigen::MatrixXd r(2 * n, 2);
    for (double& e : r.reshaped()) e = g(rng);
    coarse.apply_two_level(blocks, r, z);
    const Eigen::MatrixXd coarse_part = p * coarse.coarse_solve(r);
    Eigen::MatrixXd smoothed;
    blocks.apply(r - s.apply(coarse_part), smoothed);
    CHECK((z - coarse_part - smoothed).norm() <= 1e-12 * z.norm());
  }
}

TEST_CASE("coarse space: A E in 8-bit fixed point, each entry within half a step of its column's scale") {
  const System s(true);
  const bem::ClusterCoarseSpace exact(s.tree, s.laplace, s.yukawa, s.half_mass, 32, kExact);
  const bem::ClusterCoarseSpace narrow(s.tree, s.laplace, s.yukawa, s.half_mass, 32);
  const Eigen::Index m = exact.clusters();
  // The sums A_c do not depend on how A E is stored (to the order of parallel sums).
  CHECK((narrow.matrix() - exact.matrix()).norm() <= 1e-14 * exact.matrix().norm());

  // Block by block: the 8-bit columns decode to the exact ones within s/2, s = max|column|/127.
  using Storage = bem::HierarchicalMatrix::GroupedColumns::Storage;
  const auto a = s.laplace.group_columns(exact.cluster_of(), m, Storage::exact);
  const auto b = s.laplace.group_columns(exact.cluster_of(), m, Storage::fixed8);
  REQUIRE(a.parts.size() == b.parts.size());
  std::size_t expanded = 0, factored = 0;
  for (std::size_t k = 0; k < a.parts.size(); ++k) {
    const auto& x = a.parts[k];
    const auto& y = b.parts[k];
    REQUIRE(x.expanded == y.expanded);
    if (!x.expanded) {  // EᵀV, kept exactly in both
      ++factored;
      CHECK((x.values - y.values).norm() == 0.0);
      continue;
    }
    ++expanded;
    REQUIRE(y.values.size() == 0);
    REQUIRE(y.fixed8.size() == std::size_t(x.values.size()));
    for (Eigen::Index c = 0; c < x.values.cols(); ++c) {
      const double scale = y.scale[std::size_t(c)];
      CHECK(scale == x.values.col(c).cwiseAbs().maxCoeff() / 127.0);
      for (Eigen::Index r = 0; r < x.values.rows(); ++r)
        REQUIRE(std::abs(scale * y.fixed8[std::size_t(c * x.values.rows() + r)] - x.values(r, c)) <=
                0.5 * scale * (1.0 + 1e-12));
    }
  }
  CAPTURE(expanded, factored);
  CHECK(expanded > factored);  // most blocks meet few clusters

  // The product changes accordingly: a small relative amount, but not nothing.
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  Eigen::MatrixXd y(2 * m, 3);
  for (double& e : y.reshaped()) e = g(rng);
  const Eigen::MatrixXd reference = exact.apply_operator(y);
  const double change = (narrow.apply_operator(y) - reference).norm() / reference.norm();
  CAPTURE(change);
  CHECK(change > 1e-6);
  CHECK(change < 1e-2);
}
