// bem/hmatrix/adaptive_precision_factors.hpp: the columns of small singular value go to
// 16- and 8-bit fixed point, the stored block stays within the single-precision rounding
// bound plus β = 2^−23 σ_1, the byte count is what the formats say, and the products use
// exactly the stored (decoded) factors.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include <Eigen/QR>

#include "bem/hmatrix/adaptive_precision_factors.hpp"

using namespace bemshape;

namespace {

Eigen::MatrixXd orthonormal_columns(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd a(rows, cols);
  for (double& e : a.reshaped()) e = g(rng);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  return qr.householderQ() * Eigen::MatrixXd::Identity(rows, cols);
}

/// U = Q diag(σ) with σ_i = 3·10^{−8 i/(r−1)} (the decay of a block recompressed at ε = 1e−8)
/// and V orthonormal: recompress's output form.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> recompressed_like(Eigen::Index m, Eigen::Index n,
                                                               Eigen::Index r, std::mt19937& rng) {
  Eigen::VectorXd sigma(r);
  for (Eigen::Index i = 0; i < r; ++i) sigma(i) = 3.0 * std::pow(10.0, -8.0 * double(i) / double(r - 1));
  return {orthonormal_columns(m, r, rng) * sigma.asDiagonal(), orthonormal_columns(n, r, rng)};
}

}  // namespace

TEST_CASE("Adaptive-precision factors: fixed-point columns add at most 2^-23 sigma_1 to the "
          "single-precision rounding") {
  std::mt19937 rng(11);
  const Eigen::Index m = 200, n = 150, r = 30;
  const auto [u, v] = recompressed_like(m, n, r, rng);
  const Eigen::MatrixXd exact = u * v.transpose();
  const bem::AdaptivePrecisionFactors narrow(u, v), single(u, v, false);

  const auto stored = [&](const bem::AdaptivePrecisionFactors& f) {
    return Eigen::MatrixXd(f.u_rows(0, m) * f.v_rows(0, n).transpose());
  };
  const double single_error = (stored(single) - exact).norm();
  const double narrow_error = (stored(narrow) - exact).norm();
  const double beta = std::ldexp(u.col(0).norm() * v.col(0).norm(), -23);
  CAPTURE(single_error, narrow_error, beta);
  CHECK(single_error <= beta);  // each factor rounded to 2^−24 relative
  CHECK(narrow_error <= single_error + beta);

  // The tail of the eight decades goes to fixed point; the leading columns stay single.
  const auto c = narrow.columns();
  CAPTURE(c.single, c.fixed16, c.fixed8);
  CHECK(c.single + c.fixed16 + c.fixed8 == r);
  CHECK(c.single >= 8);
  CHECK(c.fixed16 > 0);
  CHECK(c.fixed8 > 0);
  CHECK(single.columns().single == r);
  // Bytes: 4, 2 and 1 per entry of U and V, and a double scale per fixed-point column of each.
  CHECK(narrow.bytes() == std::uint64_t((m + n) * (4 * c.single + 2 * c.fixed16 + c.fixed8) +
                                        2 * 8 * (c.fixed16 + c.fixed8)));
  CHECK(single.bytes() == std::uint64_t(4 * (m + n) * r));
  CHECK(narrow.entries() == std::uint64_t((m + n) * r));

  // The columns keep their order: column i of the stored U is σ_i û_i to its rounding.
  const Eigen::MatrixXd un = narrow.u_rows(0, m);
  for (Eigen::Index i = 0; i < r; ++i)
    CHECK((un.col(i) - u.col(i)).norm() <= 0.01 * u.col(i).norm());
}

TEST_CASE("Adaptive-precision factors: products are those of the stored factors") {
  std::mt19937 rng(5);
  const Eigen::Index m = 300, n = 260, r = 24;  // more rows than one conversion chunk
  const auto [u, v] = recompressed_like(m, n, r, rng);
  const bem::AdaptivePrecisionFactors f(u, v);
  std::normal_distribution<double> g;
  Eigen::MatrixXd x(n, 3);
  for (double& e : x.reshaped()) e = g(rng);

  Eigen::MatrixXd t;
  f.multiply_v_transpose(x, t);
  const Eigen::MatrixXd vs = f.v_rows(0, n), us = f.u_rows(0, m);
  const Eigen::MatrixXd t_expected = vs.transpose() * x;
  CHECK((t - t_expected).norm() <= 1e-14 * t_expected.norm());

  Eigen::MatrixXd out = Eigen::MatrixXd::Ones(m, 3);
  f.add_u_product(t, out);
  const Eigen::MatrixXd out_expected = Eigen::MatrixXd::Ones(m, 3) + us * t;
  CHECK((out - out_expected).norm() <= 1e-14 * out_expected.norm());

  // Row ranges decode the same values as the whole factor.
  CHECK(f.u_rows(130, 40) == us.middleRows(130, 40));
  CHECK(f.v_rows(255, 5) == vs.middleRows(255, 5));
}

TEST_CASE("Adaptive-precision factors: rank zero and zero columns") {
  const bem::AdaptivePrecisionFactors empty(Eigen::MatrixXd(7, 0), Eigen::MatrixXd(5, 0));
  CHECK(empty.rank() == 0);
  CHECK(empty.bytes() == 0);
  Eigen::MatrixXd t;
  empty.multiply_v_transpose(Eigen::MatrixXd::Ones(5, 2), t);
  CHECK(t.rows() == 0);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(7, 2);
  empty.add_u_product(t, out);
  CHECK(out.isZero(0.0));

  // A zero trailing column is stored (in 8 bits, scale 0) and decodes to zero.
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(6, 2), v = Eigen::MatrixXd::Zero(4, 2);
  u.col(0) << 1.0, 2.0, 3.3, -0.7, 0.1, 1.9;  // not representable in fixed point
  v(1, 0) = 1.0;
  const bem::AdaptivePrecisionFactors f(u, v);
  CHECK(f.columns().single == 1);
  CHECK(f.columns().fixed8 == 1);
  CHECK(f.u_rows(0, 6).col(1).isZero(0.0));
  CHECK(f.u_rows(0, 6).col(0) == u.col(0).cast<float>().cast<double>());
}
