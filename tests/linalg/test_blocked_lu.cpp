// linalg/blocked_lu.hpp: the panel-wise LU gives the same solution as Eigen's partial-pivot LU
// to rounding, keeps a zero pivot for the caller to detect, and stops between panels when
// the run is cancelled.
#include <catch2/catch.hpp>

#include <Eigen/LU>

#include "linalg/blocked_lu.hpp"
#include "core/cancellation.hpp"

using namespace bemshape;

namespace {

/// A well-conditioned but pivoting-hungry matrix: random entries plus a large entry below
/// the diagonal in every column, so that partial pivoting must swap rows.
Eigen::MatrixXd test_matrix(Eigen::Index n) {
  std::srand(7);
  Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n);
  for (Eigen::Index j = 0; j + 1 < n; ++j) a(j + 1, j) += 4.0;
  return a;
}

}  // namespace

TEST_CASE("blocked LU solves like Eigen's partial-pivot LU, across several panels") {
  // 300 = two full panels of 128 and a partial one.
  for (const Eigen::Index n : {Eigen::Index(1), Eigen::Index(5), Eigen::Index(300)}) {
    const Eigen::MatrixXd a = test_matrix(n);
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 3);
    const linalg::LuFactors f = linalg::lu_factorise(a);
    const Eigen::MatrixXd x = linalg::lu_solve(f, b);
    const Eigen::MatrixXd reference = a.partialPivLu().solve(b);
    CAPTURE(n);
    CHECK((a * x - b).norm() / b.norm() < 1e-13);
    CHECK((x - reference).norm() / reference.norm() < 1e-12);
    // Partial pivoting: every multiplier in L has magnitude at most 1.
    CHECK(f.lu.triangularView<Eigen::StrictlyLower>().toDenseMatrix().cwiseAbs().maxCoeff() <=
          1.0);
  }
}

TEST_CASE("blocked LU of a singular matrix gives a non-finite solution, not a plausible one") {
  Eigen::MatrixXd a = test_matrix(200);
  a.col(150).setZero();  // exactly singular
  const Eigen::MatrixXd x = linalg::lu_solve(linalg::lu_factorise(a), Eigen::MatrixXd::Ones(200, 1));
  CHECK_FALSE(x.allFinite());
}

TEST_CASE("blocked LU stops with CancelledError once the deadline has passed") {
  const Eigen::MatrixXd a = test_matrix(400);
  set_deadline(1e-9);
  CHECK_THROWS_AS(linalg::lu_factorise(a), CancelledError);
  clear_cancellation();
  CHECK_NOTHROW(linalg::lu_factorise(a));
}
