// linalg/fixed_point_lu.hpp: the stored factors solve a matrix within the stated
// backward error of the original, pivots are not rounded away, and the memory is 2 bytes per
// entry.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/LU>

#include "linalg/fixed_point_lu.hpp"

using namespace bemshape;

TEST_CASE("Fixed-point LU: solves a nearby matrix, with the backward error the format allows") {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  // A nonsymmetric matrix that needs pivoting (a small leading entry) and whose columns span
  // three decades (condition number about 10⁷).
  const Eigen::Index n = 203;  // not a multiple of the 8 lanes
  Eigen::MatrixXd m(n, n);
  for (double& e : m.reshaped()) e = g(rng);
  m(0, 0) = 1e-6;
  for (Eigen::Index j = 0; j < n; ++j) m.col(j) *= std::pow(10.0, 3.0 * double(j) / double(n));
  const Eigen::MatrixXf mf = m.cast<float>();
  const linalg::FixedPointLu lu(mf);
  CHECK(lu.size() == n);
  CHECK(lu.bytes() == 2 * std::uint64_t(n * n) + 16 * std::uint64_t(n));

  Eigen::MatrixXd b(n, 3);
  for (double& e : b.reshaped()) e = g(rng);
  Eigen::MatrixXd x = b;
  lu.solve_in_place(x);
  // Backward error: x solves (M + δM) x = b with ‖δM‖ about 2^−16 ‖|L||U|‖ (the rounding
  // of single precision, 2^−24, is far below): the residual relative to ‖M‖‖x‖ is of that
  // order, and far above double precision's, so the test sees the fixed-point factors.
  const Eigen::MatrixXd mfd = mf.cast<double>();
  const double backward = (mfd * x - b).norm() / (mfd.norm() * x.norm());
  CAPTURE(backward);
  CHECK(backward < 1e-4);
  CHECK(backward > 1e-9);
  // One column at a time gives the same as all three at once.
  Eigen::MatrixXd one = b.col(1);
  lu.solve_in_place(one);
  CHECK((one.col(0) - x.col(1)).norm() <= 1e-14 * x.col(1).norm());
}

TEST_CASE("Fixed-point LU: identity and a permutation are solved exactly") {
  Eigen::MatrixXf p = Eigen::MatrixXf::Zero(9, 9);
  for (int i = 0; i < 9; ++i) p(i, (i * 4) % 9) = 2.0f;  // a scaled permutation
  const linalg::FixedPointLu lu(p);
  Eigen::MatrixXd b = Eigen::VectorXd::LinSpaced(9, 1.0, 9.0), x = b;
  lu.solve_in_place(x);
  CHECK((p.cast<double>() * x - b).norm() == 0.0);
}
