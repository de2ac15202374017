// bem/evaluate/inverse_distance_taylor.hpp: the recurrence gives the closed-form
// derivatives of 1/|R|, and the truncated series converges to 1/|R − d| like (|d|/|R|)^{p+1}.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "bem/evaluate/inverse_distance_taylor.hpp"

using namespace bemshape;

TEST_CASE("multi-index table: numbered by degree, index() inverts exponent()") {
  const bem::MultiIndexTable table(7);
  REQUIRE(table.size() == bem::MultiIndexTable::count(7));
  for (int k = 0; k < table.size(); ++k) {
    const auto& e = table.exponent(k);
    CHECK(table.index(e[0], e[1], e[2]) == k);
    const int n = e[0] + e[1] + e[2];
    CHECK(k >= (n == 0 ? 0 : bem::MultiIndexTable::count(n - 1)));
    CHECK(k < bem::MultiIndexTable::count(n));
  }
}

TEST_CASE("Taylor coefficients of 1/r equal the closed-form derivatives up to degree 3") {
  const bem::MultiIndexTable table(3);
  const Eigen::Vector3d R(0.7, -1.3, 0.4);
  const double x = R(0), y = R(1), z = R(2), r = R.norm();
  const double r3 = r * r * r, r5 = r3 * r * r, r7 = r5 * r * r;
  std::vector<double> b(static_cast<size_t>(table.size() + 1));
  bem::inverse_distance_taylor(table, R, 3, b.data());
  const auto at = [&](int i, int j, int k) { return b[static_cast<size_t>(table.index(i, j, k))]; };
  CHECK(at(0, 0, 0) == Approx(1.0 / r));
  CHECK(at(1, 0, 0) == Approx(-x / r3));
  CHECK(at(0, 0, 1) == Approx(-z / r3));
  // ∂²/∂x² (1/r) = 3x²/r⁵ − 1/r³, divided by 2!.
  CHECK(at(2, 0, 0) == Approx((3 * x * x / r5 - 1 / r3) / 2));
  CHECK(at(1, 1, 0) == Approx(3 * x * y / r5));
  // ∂³/∂x³ (1/r) = −15x³/r⁷ + 9x/r⁵, divided by 3!.
  CHECK(at(3, 0, 0) == Approx((-15 * x * x * x / r7 + 9 * x / r5) / 6));
  // ∂³/∂x∂y∂z (1/r) = −15xyz/r⁷.
  CHECK(at(1, 1, 1) == Approx(-15 * x * y * z / r7));
  // ∂³/∂x²∂y (1/r) = −15x²y/r⁷ + 3y/r⁵, divided by 2!.
  CHECK(at(2, 1, 0) == Approx((-15 * x * x * y / r7 + 3 * y / r5) / 2));
}

TEST_CASE("the truncated Taylor series of 1/|R - d| converges geometrically in |d|/|R|") {
  const int degree = 16;
  const bem::MultiIndexTable table(degree);
  const Eigen::Vector3d R(1.0, 0.5, -0.8);
  const Eigen::Vector3d d = 0.3 * R.norm() * Eigen::Vector3d(-0.2, 0.9, 0.4).normalized();
  std::vector<double> b(static_cast<size_t>(table.size() + 1));
  bem::inverse_distance_taylor(table, R, degree, b.data());
  const double exact = 1.0 / (R - d).norm();
  double sum = 0.0;
  int k = 0;
  for (int p = 0; p <= degree; ++p) {
    for (; k < bem::MultiIndexTable::count(p); ++k) {
      const auto& e = table.exponent(k);
      sum += b[static_cast<size_t>(k)] * std::pow(-d(0), e[0]) * std::pow(-d(1), e[1]) *
             std::pow(-d(2), e[2]);
    }
    const double error = std::abs(sum - exact) * R.norm();
    INFO("order " << p << ": relative error " << error);
    // The terms of degree n are the Legendre series' |d|^n P_n(cos γ)/|R|^{n+1}, |P_n| ≤ 1:
    // |error|·|R| ≤ (|d|/|R|)^{p+1}/(1 − |d|/|R|).
    CHECK(error <= std::pow(0.3, p + 1) / 0.7 * (1 + 1e-12) + 1e-15);
  }
}
