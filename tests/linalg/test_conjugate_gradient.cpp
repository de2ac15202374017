// Conjugate gradients on a small SPD system with several right-hand sides: agrees with a
// dense Cholesky solve, converges in at most n steps without preconditioning, and reports
// non-convergence as NumericalError.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>

#include "core/errors.hpp"
#include "linalg/conjugate_gradient.hpp"

using namespace bemshape;
using namespace bemshape::linalg;

namespace {

struct DenseOperator {
  Eigen::MatrixXd A;
  void apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& y) const { y = A * x; }
};
struct Identity {
  void apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const { z = r; }
};
struct Jacobi {
  Eigen::VectorXd inverse;
  void apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const {
    z = (r.array().colwise() * inverse.array()).matrix();
  }
};

DenseOperator random_spd(int n) {
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
  return {B * B.transpose() + n * Eigen::MatrixXd::Identity(n, n)};
}

}  // namespace

TEST_CASE("CG matches a direct solve for several right-hand sides") {
  const auto op = random_spd(40);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(40, 3);
  Eigen::MatrixXd X;
  const Jacobi jacobi{op.A.diagonal().cwiseInverse()};
  const auto report = conjugate_gradient(op, jacobi, B, X, 1e-12, 200);
  CHECK(report.converged);
  const Eigen::MatrixXd exact = op.A.llt().solve(B);
  CHECK((X - exact).norm() <= 1e-9 * exact.norm());
  for (double r : report.relative_residuals)
    CHECK(r <= 1e-12);
}

TEST_CASE("CG terminates in at most n steps in exact arithmetic (small n)") {
  const auto op = random_spd(8);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(8, 2);
  Eigen::MatrixXd X;
  const auto report = conjugate_gradient(op, Identity{}, B, X, 1e-10, 12);
  CHECK(report.iterations <= 10);
}

TEST_CASE("CG reports failure to converge") {
  const auto op = random_spd(50);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(50, 1);
  Eigen::MatrixXd X;
  CHECK_THROWS_AS(conjugate_gradient(op, Identity{}, B, X, 1e-14, 2), NumericalError);
  const auto report = conjugate_gradient(op, Identity{}, B, X, 1e-14, 2, {}, false);
  CHECK_FALSE(report.converged);
}
