// linalg/mixed_precision_products.hpp: products of float, int16 and int8 matrices
// with per-column scales and double vectors equal the products of the widened matrix, for
// every number of right-hand sides (they are taken four at a time), row counts that are not
// multiples of the 8 partial sums or the 256-row blocks, and strided operands.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>

#include "linalg/mixed_precision_products.hpp"

using namespace bemshape;

namespace {

template <class T>
void check_products(std::mt19937& rng) {
  const Eigen::Index rows = 517, cols = 13;  // 517 = 2·256 + 5 = 64·8 + 5
  std::uniform_int_distribution<int> level(-100, 100);
  std::normal_distribution<double> g;
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> a(rows, cols);
  for (auto& e : a.reshaped()) e = T(level(rng)) / T(std::is_floating_point_v<T> ? 7 : 1);
  Eigen::VectorXd scale(cols);
  for (double& s : scale) s = std::exp(g(rng));
  // A widened, exactly: the reference products are Eigen's in double precision.
  const Eigen::MatrixXd wide = a.template cast<double>() * scale.asDiagonal();
  for (Eigen::Index k = 1; k <= 6; ++k) {
    CAPTURE(k);
    // Y += A S C into rows 3 … 3 + rows of a larger matrix (outer stride ≠ rows).
    Eigen::MatrixXd c(cols, k), big = Eigen::MatrixXd::Constant(rows + 10, k, 0.5);
    for (double& e : c.reshaped()) e = g(rng);
    linalg::add_scaled_columns(a.data(), rows, rows, cols, scale.data(), c, big.middleRows(3, rows));
    const Eigen::MatrixXd y_expected = Eigen::MatrixXd::Constant(rows, k, 0.5) + wide * c;
    CHECK((big.middleRows(3, rows) - y_expected).norm() <= 1e-14 * y_expected.norm());
    CHECK(big.topRows(3).isConstant(0.5, 0.0));
    CHECK(big.bottomRows(7).isConstant(0.5, 0.0));
    // T += S Aᵀ X.
    Eigen::MatrixXd x(rows, k), t = Eigen::MatrixXd::Ones(cols, k);
    for (double& e : x.reshaped()) e = g(rng);
    linalg::add_scaled_column_dots(a.data(), rows, rows, cols, scale.data(), x, t);
    const Eigen::MatrixXd t_expected = Eigen::MatrixXd::Ones(cols, k) + wide.transpose() * x;
    CHECK((t - t_expected).norm() <= 1e-14 * t_expected.norm());
  }
  // No scales: the stored values themselves; a leading dimension larger than the rows used
  // (the first 200 rows of A).
  Eigen::MatrixXd c = Eigen::MatrixXd::Ones(cols, 3), y = Eigen::MatrixXd::Zero(200, 3);
  linalg::add_scaled_columns(a.data(), rows, 200, cols, nullptr, c, y);
  const Eigen::VectorXd sums = a.template cast<double>().topRows(200).rowwise().sum();
  CHECK((y.col(2) - sums).norm() <= 1e-14 * sums.norm());
}

}  // namespace

TEST_CASE("Mixed-precision products: float, int16 and int8 columns equal the widened products") {
  std::mt19937 rng(11);
  check_products<float>(rng);
  check_products<std::int16_t>(rng);
  check_products<std::int8_t>(rng);
}
