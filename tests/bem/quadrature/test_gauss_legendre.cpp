#include <catch2/catch.hpp>
#include <cmath>

#include "bem/quadrature/gauss_legendre.hpp"
#include "core/errors.hpp"

using bemshape::bem::gauss_legendre;

TEST_CASE("Gauss-Legendre: two-point rule is ±1/sqrt(3) with unit weights", "[gauss_legendre]") {
  const auto& rule = gauss_legendre(2);
  CHECK(rule.nodes[0] == Approx(-1.0 / std::sqrt(3.0)).epsilon(1e-15));
  CHECK(rule.nodes[1] == Approx(1.0 / std::sqrt(3.0)).epsilon(1e-15));
  CHECK(rule.weights[0] == Approx(1.0).epsilon(1e-15));
}

TEST_CASE("Gauss-Legendre: n points integrate monomials up to degree 2n-1 exactly",
          "[gauss_legendre]") {
  for (int n = 1; n <= bemshape::bem::max_gauss_legendre_points; ++n) {
    const auto& rule = gauss_legendre(n);
    REQUIRE(rule.size() == n);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i)
        sum += rule.weights[static_cast<size_t>(i)] * std::pow(rule.nodes[static_cast<size_t>(i)], k);
      const double exact = (k % 2 == 1) ? 0.0 : 2.0 / (k + 1);
      INFO("n = " << n << ", k = " << k);
      CHECK(std::abs(sum - exact) < 1e-14);
    }
  }
}

TEST_CASE("Gauss-Legendre: converges exponentially for an analytic function",
          "[gauss_legendre]") {
  // ∫_{−1}^{1} 1/(1 + t²/4) dt = 4 atan(1/2), poles at ±2i.
  const double exact = 4.0 * std::atan(0.5);
  const auto& rule = gauss_legendre(30);
  double sum = 0.0;
  for (int i = 0; i < 30; ++i) {
    const double t = rule.nodes[static_cast<size_t>(i)];
    sum += rule.weights[static_cast<size_t>(i)] / (1.0 + 0.25 * t * t);
  }
  CHECK(std::abs(sum - exact) < 1e-14);
}

TEST_CASE("Gauss-Legendre: invalid sizes are internal errors", "[gauss_legendre]") {
  CHECK_THROWS_AS(gauss_legendre(0), bemshape::InternalError);
  CHECK_THROWS_AS(gauss_legendre(bemshape::bem::max_gauss_legendre_points + 1),
                  bemshape::InternalError);
}
