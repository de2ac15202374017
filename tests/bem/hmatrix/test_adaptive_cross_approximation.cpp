// bem/hmatrix/adaptive_cross_approximation.hpp: ACA reproduces low-rank matrices
// exactly, approximates a smooth kernel between separated clusters to its tolerance with a
// small rank, and gives rank 0 for a zero block; recompression keeps the rank of the
// truncated SVD within the tolerance.
#include <catch2/catch.hpp>
#include <random>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "bem/hmatrix/adaptive_cross_approximation.hpp"

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

/// The smallest r with (Σ_{r<i≤k} σ_i²)^{1/2} ≤ ε (Σ_{i≤k} σ_i²)^{1/2}: the rank of the
/// truncated SVD of A_k at relative tolerance ε.
int optimal_rank(const Eigen::VectorXd& sigma, int k, double epsilon) {
  const double total2 = sigma.head(k).squaredNorm();
  int optimal = k;
  while (optimal > 0 && sigma.segment(optimal - 1, k - optimal + 1).squaredNorm() <= epsilon * epsilon * total2)
    --optimal;
  return optimal;
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
    const int optimal = optimal_rank(sigma, k, epsilon);
    const bem::LowRankBlock r = bem::recompress(factors, epsilon);
    CAPTURE(epsilon, optimal, r.rank());
    CHECK(r.rank() == optimal);
    CHECK((r.U * r.V.transpose() - ak).norm() <= 1.01 * epsilon * ak.norm() + 1e-15 * ak.norm());
  }
}

TEST_CASE("recompression by Gram matrices: ACA-like factors, the same ranks and errors as by Householder") {
  // Factors shaped like ACA's: U Vᵀ = A_k with u_l = Σ_{i≥l} σ_i M_il x_i (each column
  // mostly its own singular direction, as a cross vanishes on the pivots before it) and
  // v_l = Σ_{i≤l} (M⁻ᵀ)_il y_i, for M unit lower triangular: columns of decaying norms that
  // are well conditioned once scaled, which is what the Gram route needs.
  const Eigen::MatrixX3d x = random_cloud(120, Eigen::Vector3d::Zero(), 6);
  const Eigen::MatrixX3d y = random_cloud(90, Eigen::Vector3d(3.0, 0.5, 0.0), 7);
  const Eigen::MatrixXd a = inverse_distances(x, y);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const int k = 30;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> uniform(-0.2, 0.2);
  Eigen::MatrixXd mix = Eigen::MatrixXd::Identity(k, k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < i; ++j) mix(i, j) = uniform(rng);
  bem::LowRankBlock factors;
  factors.U = svd.matrixU().leftCols(k) * sigma.head(k).asDiagonal() * mix;
  factors.V = svd.matrixV().leftCols(k) * mix.inverse().transpose();
  const Eigen::MatrixXd ak = factors.U * factors.V.transpose();
  for (const double epsilon : {1e-4, 1e-6, 1e-8, 1e-12}) {
    const int optimal = optimal_rank(sigma, k, epsilon);
    CAPTURE(epsilon, optimal);
    // At 1e−12 the route needs scaled columns within a factor of about 3 of orthogonal
    // (the rounding u κ against ε); either route must then meet the tolerance.
    if (epsilon >= 1e-8) CHECK(bem::recompression_uses_gram_bases(factors, epsilon));
    const bem::LowRankBlock gram = bem::recompress(factors, epsilon);
    const bem::LowRankBlock householder = bem::recompress(factors, epsilon, bem::FactorBases::householder);
    CHECK(gram.rank() == optimal);
    CHECK(householder.rank() == optimal);
    for (const bem::LowRankBlock* r : {&gram, &householder}) {
      CHECK((r->U * r->V.transpose() - ak).norm() <= 1.01 * epsilon * ak.norm() + 1e-15 * ak.norm());
      // recompress's output form: V' orthonormal, U' with orthogonal columns.
      const Eigen::MatrixXd vv = r->V.transpose() * r->V;
      CHECK((vv - Eigen::MatrixXd::Identity(vv.rows(), vv.cols())).norm() < 1e-6);
      Eigen::MatrixXd uu = r->U.transpose() * r->U;
      uu.diagonal().setZero();
      CHECK(uu.norm() < 1e-6 * r->U.squaredNorm());
    }
    CHECK((gram.U * gram.V.transpose() - householder.U * householder.V.transpose()).norm() <=
          2.02 * epsilon * ak.norm());
  }
  // A redundant factorisation has rank-deficient columns: Householder it is.
  bem::LowRankBlock redundant;
  redundant.U.resize(120, 2 * k);
  redundant.V.resize(90, 2 * k);
  redundant.U << factors.U, factors.U;
  redundant.V << 0.5 * factors.V, 0.5 * factors.V;
  CHECK(!bem::recompression_uses_gram_bases(redundant, 1e-8));
  CHECK(bem::recompress(redundant, 1e-8).rank() == bem::recompress(factors, 1e-8).rank());
}
