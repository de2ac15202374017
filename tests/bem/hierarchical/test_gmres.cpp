// bem/hierarchical/gmres.hpp: restarted GMRES on small non-symmetric systems against a
// direct solve; the reported residual is the true one; an exact preconditioner converges in
// one step; a singular, inconsistent system is reported as not converged.
#include <catch2/catch.hpp>
#include <random>

#include <Eigen/LU>

#include "bem/hierarchical/gmres.hpp"

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
}  // namespace

TEST_CASE("GMRES: restarted solve of a non-symmetric system, true residual reported") {
  const int n = 200;
  const Eigen::MatrixXd a = test_matrix(n, 3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const bem::LinearOperator op = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = a * x; };
  Eigen::VectorXd x;
  bem::GmresOptions options;
  options.tolerance = 1e-10;
  options.restart = 8;  // forces restarts
  const bem::GmresResult r = bem::gmres(op, {}, b, x, options);
  CHECK(r.converged);
  CHECK(r.residual <= 1e-10);
  CHECK(r.residual == Approx((b - a * x).norm() / b.norm()).epsilon(1e-3).margin(1e-14));
  CHECK((x - a.partialPivLu().solve(b)).norm() < 1e-8 * x.norm());

  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  const bem::LinearOperator exact = [&](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = lu.solve(v); };
  Eigen::VectorXd x2;
  const bem::GmresResult r2 = bem::gmres(op, exact, b, x2, options);
  CHECK(r2.converged);
  CHECK(r2.iterations == 1);
}

TEST_CASE("GMRES: an inconsistent singular system is reported as not converged") {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(10, 10);
  a(9, 9) = 0.0;
  Eigen::VectorXd b = Eigen::VectorXd::Ones(10);
  const bem::LinearOperator op = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = a * x; };
  Eigen::VectorXd x;
  const bem::GmresResult r = bem::gmres(op, {}, b, x);
  CHECK(!r.converged);
  CHECK(r.residual == Approx(1.0 / std::sqrt(10.0)).epsilon(1e-6));
}
