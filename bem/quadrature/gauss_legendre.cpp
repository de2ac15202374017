#include "bem/quadrature/gauss_legendre.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

/// Newton stops when the step is below this: the roots are then correct to rounding
/// (|P_n'| is large at the roots, so the last step is far below the node spacing).
constexpr double newton_step_tolerance = 1e-15;
/// Newton converges quadratically from the Tricomi-type initial guess; 100 iterations is a
/// bound that is never reached, kept so that a bug cannot hang the program.
constexpr int max_newton_iterations = 100;

/// (P_n(t), P_n'(t)) by the three-term recurrence.
std::array<double, 2> legendre_with_derivative(int n, double t) {
  double p0 = 1.0, p1 = t;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  const double pn = n == 0 ? 1.0 : p1;
  const double pn_minus_1 = n == 0 ? 0.0 : (n == 1 ? 1.0 : p0);
  const double derivative = n * (t * pn - pn_minus_1) / (t * t - 1.0);
  return {pn, derivative};
}

}  // namespace

GaussLegendreRule compute_gauss_legendre(int n) {
  if (n < 1) throw InternalError("gauss_legendre: n = " + std::to_string(n) + " < 1");
  GaussLegendreRule rule;
  rule.nodes.assign(static_cast<size_t>(n), 0.0);
  rule.weights.assign(static_cast<size_t>(n), 0.0);
  // Roots are symmetric: compute the ones in (0, 1) (and 0 for odd n) and mirror them.
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double t = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int it = 0; it < max_newton_iterations; ++it) {
      const auto [p, dp] = legendre_with_derivative(n, t);
      const double step = p / dp;
      t -= step;
      derivative = dp;
      if (std::abs(step) < newton_step_tolerance) {
        derivative = legendre_with_derivative(n, t)[1];
        break;
      }
    }
    const double w = 2.0 / ((1.0 - t * t) * derivative * derivative);
    const auto lo = static_cast<size_t>(i), hi = static_cast<size_t>(n - 1 - i);
    rule.nodes[lo] = -t;
    rule.nodes[hi] = t;
    rule.weights[lo] = w;
    rule.weights[hi] = w;
  }
  if (n % 2 == 1) rule.nodes[static_cast<size_t>(n / 2)] = 0.0;
  return rule;
}

const GaussLegendreRule& gauss_legendre(int n) {
  static const std::vector<GaussLegendreRule> cache = [] {
    std::vector<GaussLegendreRule> rules;
    rules.reserve(max_gauss_legendre_points + 1);
    rules.emplace_back();  // index 0 unused
    for (int k = 1; k <= max_gauss_legendre_points; ++k) rules.push_back(compute_gauss_legendre(k));
    return rules;
  }();
  if (n < 1 || n > max_gauss_legendre_points)
    throw InternalError("gauss_legendre: n = " + std::to_string(n) + " outside [1, " +
                        std::to_string(max_gauss_legendre_points) + "]");
  return cache[static_cast<size_t>(n)];
}

}  // namespace bemshape::bem
