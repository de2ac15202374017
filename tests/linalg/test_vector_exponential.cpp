#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "linalg/vector_exponential.hpp"

using bemshape::linalg::vector_exp;

namespace {
/// |e − e^x| / e^x with e^x in long double (64-bit mantissa on x86-64), the reference.
double relative_error(double value, double x) {
  const long double exact = std::exp(static_cast<long double>(x));
  return static_cast<double>(std::fabs(static_cast<long double>(value) - exact) / exact);
}
}  // namespace

TEST_CASE("vector_exp: within 6e-16 of e^x from -708 to 709, in every lane and the tail",
          "[vector_exponential]") {
  // 200003 arguments (not a multiple of 4: the last three take the scalar tail), densest
  // where the kernels use them (−40 ≤ x ≤ 10), and the reduction's boundaries x = (j + ½) ln 2.
  Eigen::ArrayXd x(200003);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double u = double(i) / double(x.size() - 1);
    x(i) = i % 2 == 0 ? -708.0 + 1417.0 * u : -40.0 + 50.0 * u;
  }
  for (int j = -1020; j <= 1020 && j * 0.6931 < 700.0; j += 7)
    x(100000 + j) = (j + 0.5) * 0.69314718055994530942;
  const Eigen::ArrayXd e = vector_exp<Eigen::ArrayXd>(x);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    worst = std::max(worst, relative_error(e(i), x(i)));
  INFO("largest relative error " << worst);
  CHECK(worst < 6e-16);
  CHECK(worst > 0.0);  // the comparison sees rounding, so it is not comparing e with itself
}

TEST_CASE("vector_exp: exact and limiting values, short arrays, fixed sizes, expressions",
          "[vector_exponential]") {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::Array<double, 8, 1> x;
  x << 0.0, -708.5, -inf, nan, 1.0, -1.0, 709.0, -745.0;
  const Eigen::Array<double, 8, 1> e = vector_exp<Eigen::Array<double, 8, 1>>(x);
  // Below −708: exactly 0 with the AVX2 scheme. Eigen's own exp (AVX-512 and plain builds)
  // clamps at about −709.4 instead and returns e^max(x, −709.4), below e^−708 ≈ 3.3e−308.
#if defined(BEMSHAPE_VECTOR_EXPONENTIAL_AVX2)
  const auto negligible = [](double v) { return v == 0.0; };
#else
  const auto negligible = [](double v) { return v >= 0.0 && v <= std::exp(-708.0); };
#endif
  CHECK(e(0) == 1.0);
  CHECK(negligible(e(1)));
  CHECK(negligible(e(2)));
  CHECK(std::isnan(e(3)));
  CHECK(relative_error(e(4), 1.0) < 6e-16);
  CHECK(relative_error(e(5), -1.0) < 6e-16);
  CHECK(relative_error(e(6), 709.0) < 6e-16);
  CHECK(negligible(e(7)));
  // Every length from 1 to 9, as a dynamic array with a fixed maximum (the quadrature's
  // chunks) and from an expression: the same values lane for lane as the whole array's.
  using Chunk = Eigen::Array<double, Eigen::Dynamic, 1, 0, 16, 1>;
  for (Eigen::Index n = 1; n <= 9; ++n) {
    const Chunk c = Chunk::LinSpaced(n, -3.0, 2.0);
    const Chunk from_expression = vector_exp<Chunk>(2.0 * c - 1.0);
    REQUIRE(from_expression.size() == n);
    for (Eigen::Index i = 0; i < n; ++i)
      CHECK(relative_error(from_expression(i), 2.0 * c(i) - 1.0) < 6e-16);
  }
}
