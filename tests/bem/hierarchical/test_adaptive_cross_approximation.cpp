// bem/hierarchical/adaptive_cross_approximation.hpp: ACA reproduces low-rank matrices
// exactly, approximates a smooth kernel between separated clusters to its tolerance with a
// small rank, and gives rank 0 for a zero block; recompression keeps the rank of the
// truncated SVD within the tolerance.
#include <catch2/catch.hpp>
#include <random>

#include <Eigen/SVD>

#include "bem/hierarchical/adaptive_cross_approximation.hpp"

using namespace bemshape;

namespace {

bem::RowGenerator rows_of(const Eigen::MatrixXd& a) {
  return [&a](Eigen::Index i, Eigen::Ref<Eigen::VectorXd> r) { r = a.row(i).transpose(); };
}
bem::ColumnGenerator columns_of(const Eigen::MatrixXd& a) {
  return [&a](Eigen::Index j, Eigen::Ref<Eigen::VectorXd> c) { c = a.col(j); };
}

Eigen::MatrixX3d random_cloud(int n, const Eigen::Vector3d& centre, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Eigen::MatrixX3d p(n, 3);
  for (int i = 0; i < n; ++i) p.row(i) = (centre + Eigen::Vector3d(u(rng), u(rng), u(rng))).transpose();
  return p;
}

/// The 1/r kernel between the points of x (rows) and y (columns).
Eigen::MatrixXd inverse_distances(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) {
  Eigen::MatrixXd a(x.rows(), y.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index j = 0; j < y.rows(); ++j) a(i, j) = 1.0 / (x.row(i) - y.row(j)).norm();
  return a;
}

}  // namespace

TEST_CASE("ACA: the 1/r kernel between clusters two diameters apart, to the tolerance") {
  const Eigen::MatrixX3d x = random_cloud(150, Eigen::Vector3d::Zero(), 1);
  const Eigen::MatrixX3d y = random_cloud(120, Eigen::Vector3d(3.5, 0.5, 0.0), 2);
  const Eigen::MatrixXd a = inverse_distances(x, y);
  for (const double epsilon : {1e-4, 1e-8}) {
    const auto lr = bem::adaptive_cross_approximation(150, 120, rows_of(a), columns_of(a), epsilon, 60);
    REQUIRE(lr.has_value());
    const double error = (a - lr->U * lr->V.transpose()).norm() / a.norm();
    CAPTURE(epsilon, lr->rank(), error);
    CHECK(error < 10.0 * epsilon);
    CHECK(lr->rank() < 40);
  }
  // A rank cap below what the tolerance needs: no approximation.
  CHECK(!bem::adaptive_cross_approximation(150, 120, rows_of(a), columns_of(a), 1e-12, 3));
}

TEST_CASE("ACA: exact on a rank-3 matrix, rank 0 on a zero block, zero rows skipped") {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  Eigen::MatrixXd u(40, 3), v(30, 3);
  for (double& e : u.reshaped()) e = g(rng);
  for (double& e : v.reshaped()) e = g(rng);
  Eigen::MatrixXd a = u * v.transpose();
  a.topRows(10).setZero();  // as the double layer between coplanar panels
  const auto lr = bem::adaptive_cross_approximation(40, 30, rows_of(a), columns_of(a), 1e-10, 20);
  REQUIRE(lr.has_value());
  CHECK(lr->rank() == 3);
  CHECK((a - lr->U * lr->V.transpose()).norm() < 1e-12 * a.norm());

  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(20, 25);
  const auto none = bem::adaptive_cross_approximation(20, 25, rows_of(zero), columns_of(zero), 1e-8, 10);
  REQUIRE(none.has_value());
  CHECK(none->rank() == 0);
}

TEST_CASE("recompression: rank of a redundant factorisation drops to the true rank") {
  std::mt19937 rng(9);
  std::normal_distribution<double> g;
  Eigen::MatrixXd u(50, 2), v(60, 2);
  for (double& e : u.reshaped()) e = g(rng);
  for (double& e : v.reshaped()) e = g(rng);
  bem::LowRankBlock redundant;
  redundant.U.resize(50, 6);
  redundant.V.resize(60, 6);
  redundant.U << u, 2.0 * u, -u;  // U Vᵀ = u(v + 2v − v)ᵀ = 2 u vᵀ
  redundant.V << v, v, v;
  const bem::LowRankBlock r = bem::recompress(redundant, 1e-12);
  CHECK(r.rank() == 2);
  CHECK((r.U * r.V.transpose() - 2.0 * u * v.transpose()).norm() < 1e-12 * (u * v.transpose()).norm());
}

TEST_CASE("recompression: the truncated SVD's rank and error at tolerances down to 1e-12") {
  // A redundant factorisation (ACA's overshoot, and more) of the 1/r kernel between two
  // clouds 3 diameters apart, whose singular values decay geometrically down to rounding.
  const Eigen::MatrixX3d x = random_cloud(120, Eigen::Vector3d::Zero(), 4);
  const Eigen::MatrixX3d y = random_cloud(90, Eigen::Vector3d(3.0, 0.5, 0.0), 5);
  const Eigen::MatrixXd a = inverse_distances(x, y);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const int k = 40;  // redundant: U Vᵀ = A_k split over two copies of its factors
  bem::LowRankBlock factors;
  factors.U.resize(120, 2 * k);
  factors.V.resize(90, 2 * k);
  const Eigen::MatrixXd us = svd.matrixU().leftCols(k) * sigma.head(k).asDiagonal();
  factors.U << 0.25 * us, 0.75 * us;
  factors.V << svd.matrixV().leftCols(k), svd.matrixV().leftCols(k);
  const Eigen::MatrixXd ak = us * svd.matrixV().leftCols(k).transpose();
  for (const double epsilon : {1e-4, 1e-8, 1e-10, 1e-12}) {
    // The optimal rank: the smallest r with (Σ_{i>r} σ_i²)^{1/2} ≤ ε ‖A_k‖_F.
    const double total2 = sigma.head(k).squaredNorm();
    int optimal = k;
    while (optimal > 0 && sigma.segment(optimal - 1, k - optimal + 1).squaredNorm() <= epsilon * epsilon * total2)
      --optimal;
    const bem::LowRankBlock r = bem::recompress(factors, epsilon);
    CAPTURE(epsilon, optimal, r.rank());
    CHECK(r.rank() == optimal);
    CHECK((r.U * r.V.transpose() - ak).norm() <= 1.01 * epsilon * ak.norm() + 1e-15 * ak.norm());
  }
}
