#include <catch2/catch.hpp>
#include <cmath>

#include "bem/quadrature/triangle_quadrature.hpp"
#include "core/errors.hpp"

using namespace bemshape::bem;

namespace {

/// ∫_{T̂} ξ^i η^j dA / |T̂| = 2 i! j! / (i + j + 2)!.
double monomial_mean(int i, int j) {
  return 2.0 * std::tgamma(i + 1.0) * std::tgamma(j + 1.0) / std::tgamma(i + j + 3.0);
}

void check_exactness(const TriangleRule& rule) {
  for (int q = 0; q < rule.size(); ++q) {
    const auto k = static_cast<size_t>(q);
    CHECK(rule.weight[k] > 0.0);
    CHECK(rule.xi[k] > 0.0);
    CHECK(rule.eta[k] > 0.0);
    CHECK(rule.xi[k] + rule.eta[k] < 1.0);
  }
  for (int i = 0; i <= rule.degree; ++i)
    for (int j = 0; i + j <= rule.degree; ++j) {
      double sum = 0.0;
      for (int q = 0; q < rule.size(); ++q) {
        const auto k = static_cast<size_t>(q);
        sum += rule.weight[k] * std::pow(rule.xi[k], i) * std::pow(rule.eta[k], j);
      }
      INFO("degree " << rule.degree << ", monomial xi^" << i << " eta^" << j);
      CHECK(std::abs(sum - monomial_mean(i, j)) < 1e-14);
    }
}

}  // namespace

TEST_CASE("symmetric triangle rules are exact to their degree with published point counts",
          "[triangle_quadrature]") {
  const int expected_points[] = {1, 3, 6, 7, 12, 16};
  int k = 0;
  for (int degree : symmetric_triangle_degrees) {
    const TriangleRule& rule = symmetric_triangle_rule(degree);
    CHECK(rule.degree == degree);
    CHECK(rule.size() == expected_points[k++]);
    check_exactness(rule);
  }
  // A degree without its own rule gets the next higher one.
  CHECK(symmetric_triangle_rule(3).degree == 4);
  CHECK(symmetric_triangle_rule(7).degree == 8);
  CHECK_THROWS_AS(symmetric_triangle_rule(9), bemshape::InternalError);
}

TEST_CASE("symmetric triangle rules are invariant under permutation of the corners",
          "[triangle_quadrature]") {
  // Rotating and reflecting the corners maps (ξ, η) to (η, 1 − ξ − η) and (η, ξ): each rule's
  // point set, with its weights, must map onto itself.
  for (int degree : symmetric_triangle_degrees) {
    const TriangleRule& rule = symmetric_triangle_rule(degree);
    auto contains = [&](double x, double y, double w) {
      for (int p = 0; p < rule.size(); ++p) {
        const auto m = static_cast<size_t>(p);
        if (std::abs(rule.xi[m] - x) < 1e-14 && std::abs(rule.eta[m] - y) < 1e-14 &&
            rule.weight[m] == w)
          return true;
      }
      return false;
    };
    for (int q = 0; q < rule.size(); ++q) {
      const auto k = static_cast<size_t>(q);
      CHECK(contains(rule.eta[k], 1.0 - rule.xi[k] - rule.eta[k], rule.weight[k]));
      CHECK(contains(rule.eta[k], rule.xi[k], rule.weight[k]));
    }
  }
}

TEST_CASE("collapsed Gauss rules are exact to degree 2n-2", "[triangle_quadrature]") {
  for (int n : {1, 2, 4, 6, 8, 12}) {
    const TriangleRule& rule = collapsed_gauss_rule(n);
    CHECK(rule.size() == n * n);
    CHECK(rule.degree == 2 * n - 2);
    check_exactness(rule);
  }
}
