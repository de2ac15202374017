// linalg/gmres.hpp: restarted GMRES on small non-symmetric systems against a
// direct solve; the reported residual is the true one; an exact preconditioner converges in
// one step on either side; preconditioned on the left, the tolerance bounds the
// preconditioned residual; a singular, inconsistent system is reported as not converged.
#include <catch2/catch.hpp>
#include <algorithm>
#include <random>
#include <vector>

#include <Eigen/LU>

#include "linalg/gmres.hpp"

using namespace bemshape;

namespace {
Eigen::MatrixXd test_matrix(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd a(n, n);
  for (double& e : a.reshaped()) e = g(rng) / std::sqrt(double(n));
  a.diagonal().array() += 2.0;  // eigenvalues clustered around 2: well conditioned
  return a;
}

/// M⁻¹ = A⁻¹ by an LU factorisation of A: GMRES converges in one step on either side.
linalg::LinearOperator exact_inverse(const Eigen::MatrixXd& a) {
  return [lu = Eigen::PartialPivLU<Eigen::MatrixXd>(a)](const Eigen::VectorXd& v, Eigen::VectorXd& z) {
    z = lu.solve(v);
  };
}
}  // namespace

TEST_CASE("GMRES: restarted solve of a non-symmetric system, true residual reported") {
  const int n = 200;
  const Eigen::MatrixXd a = test_matrix(n, 3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const linalg::LinearOperator op = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = a * x; };
  Eigen::VectorXd x;
  linalg::GmresOptions options;
  options.tolerance = 1e-10;
  options.restart = 8;  // forces restarts
  const linalg::GmresResult r = linalg::gmres(op, {}, b, x, options);
  CHECK(r.converged);
  CHECK(r.residual <= 1e-10);
  CHECK(r.residual == Approx((b - a * x).norm() / b.norm()).epsilon(1e-3).margin(1e-14));
  CHECK((x - a.partialPivLu().solve(b)).norm() < 1e-8 * x.norm());

  Eigen::VectorXd x2;
  const linalg::GmresResult r2 = linalg::gmres(op, exact_inverse(a), b, x2, options);
  CHECK(r2.converged);
  CHECK(r2.iterations == 1);
}

TEST_CASE("GMRES preconditioned on the left: the tolerance bounds M⁻¹ times the residual") {
  const int n = 180;
  // Rows scaled over three decades: A = D B with B well conditioned, M = D. The equations'
  // residual weights the rows by D; the preconditioned residual B(x* − x) does not.
  Eigen::MatrixXd a = test_matrix(n, 5);
  const Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, -3.0, 0.0).unaryExpr([](double e) {
    return std::pow(10.0, e);
  });
  a = d.asDiagonal() * a;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 0.0, 4.0).array().cos();
  const Eigen::VectorXd exact = a.partialPivLu().solve(b);
  const linalg::LinearOperator op = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = a * x; };
  const linalg::LinearOperator scaling = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z = r.cwiseQuotient(d);
  };
  linalg::GmresOptions options;
  options.tolerance = 1e-8;
  options.restart = 9;  // restarts, each ending with the true and the preconditioned residual
  options.side = linalg::PreconditionerSide::left;
  Eigen::VectorXd x;
  const linalg::GmresResult r = linalg::gmres(op, scaling, b, x, options);
  CAPTURE(r.iterations, r.residual, r.preconditioned_residual);
  CHECK(r.converged);
  CHECK(r.iterations > 9);
  const Eigen::VectorXd scaled_b = b.cwiseQuotient(d);
  CHECK(r.preconditioned_residual <= 1e-8);
  CHECK(r.preconditioned_residual ==
        Approx((b - a * x).cwiseQuotient(d).norm() / scaled_b.norm()).epsilon(1e-3).margin(1e-15));
  CHECK(r.residual == Approx((b - a * x).norm() / b.norm()).epsilon(1e-3).margin(1e-15));
  // B(x* − x) = M⁻¹r and ‖B⁻¹‖ is about 1/2 (eigenvalues around 2): the error follows.
  CHECK((x - exact).norm() <= 1e-8 * scaled_b.norm());

  // An exact preconditioner: M⁻¹A = I, one step.
  Eigen::VectorXd x2;
  const linalg::GmresResult r2 = linalg::gmres(op, exact_inverse(a), b, x2, options);
  CHECK(r2.converged);
  CHECK(r2.iterations == 1);
  CHECK((x2 - exact).norm() <= 1e-10 * exact.norm());
}

TEST_CASE("GMRES: an inconsistent singular system is reported as not converged") {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(10, 10);
  a(9, 9) = 0.0;
  Eigen::VectorXd b = Eigen::VectorXd::Ones(10);
  const linalg::LinearOperator op = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = a * x; };
  Eigen::VectorXd x;
  const linalg::GmresResult r = linalg::gmres(op, {}, b, x);
  CHECK(!r.converged);
  CHECK(r.residual == Approx(1.0 / std::sqrt(10.0)).epsilon(1e-6));
}

TEST_CASE("GMRES in lockstep: each column as if solved alone, one product per step for all") {
  const auto side = GENERATE(linalg::PreconditionerSide::right, linalg::PreconditionerSide::left);
  CAPTURE(side == linalg::PreconditionerSide::left);
  const int n = 150;
  const Eigen::MatrixXd a = test_matrix(n, 11);
  Eigen::MatrixXd b(n, 4);
  b.col(0) = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  b.col(1).setZero();                                         // done at once, x = 0
  b.col(2) = a.col(5);                                        // x = e_5
  b.col(3) = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0).array().sin();
  linalg::GmresOptions options;
  options.tolerance = 1e-9;
  options.restart = 7;  // several restarts, at different steps for different columns
  options.side = side;
  // A diagonal (Jacobi) preconditioner, so that the preconditioned path is exercised.
  const Eigen::VectorXd inverse_diagonal = a.diagonal().cwiseInverse();

  int block_products = 0, columns_multiplied = 0;
  const linalg::ColumnsOperator a_columns = [&](const Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
    ++block_products;
    columns_multiplied += int(x.cols());
    y = a * x;
  };
  const linalg::ColumnsOperator m_columns = [&](const Eigen::MatrixXd& r, Eigen::MatrixXd& z) {
    z = inverse_diagonal.asDiagonal() * r;
  };
  Eigen::MatrixXd x;
  const std::vector<linalg::GmresResult> together = linalg::gmres_columns(a_columns, m_columns, b, x, options);
  REQUIRE(together.size() == 4);

  int separate_products = 0;
  const linalg::LinearOperator a_vector = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    ++separate_products;
    y = a * v;
  };
  const linalg::LinearOperator m_vector = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z = inverse_diagonal.cwiseProduct(r);
  };
  for (int c = 0; c < 4; ++c) {
    Eigen::VectorXd xc;
    const linalg::GmresResult alone = linalg::gmres(a_vector, m_vector, b.col(c), xc, options);
    CHECK(together[size_t(c)].converged);
    CHECK(together[size_t(c)].iterations == alone.iterations);
    CHECK(together[size_t(c)].residual == Approx(alone.residual).epsilon(1e-6).margin(1e-15));
    CHECK((x.col(c) - xc).norm() <= 1e-12 * std::max(1.0, xc.norm()));
    if (c != 1)
      CHECK((b.col(c) - a * x.col(c)).norm() <= 1e-9 * b.col(c).norm());
  }
  CHECK(together[1].iterations == 0);
  CHECK(x.col(1).isZero(0.0));
  CHECK((x.col(2) - Eigen::VectorXd::Unit(n, 5)).norm() < 1e-8);
  // The same products as alone, but gathered: as many blocks as the slowest column needs.
  CHECK(columns_multiplied == separate_products);
  int slowest = 0;
  for (const auto& r : together) slowest = std::max(slowest, r.iterations);
  CHECK(block_products < separate_products);
  CHECK(block_products <= slowest + slowest / (options.restart - 1) + 2);
}
