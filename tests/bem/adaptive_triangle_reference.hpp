#pragma once
// Brute-force reference for panel integrals: globally adaptive 4-way (midpoint) subdivision
// of the triangle, each leaf integrated with the 12 × 12 collapsed Gauss rule and given the
// error estimate |I(leaf) − Σ I(children)|; the leaf with the largest estimate is refined until
// the sum of estimates is below max(rel_tol·|I|, abs_tol). Independent of the polar scheme
// (no closed forms, no change of variables), slow, and robust for every target not exactly on
// the closure of the triangle with a non-integrable singularity.

#include <functional>

#include <Eigen/Core>

namespace bemshape::testing {

struct AdaptiveResult {
  double value = 0;
  double error_estimate = 0;
  int leaves = 0;
};

/// ∫_T f(y) dA_y over the triangle (a, b, c).
AdaptiveResult adaptive_triangle_integral(const std::function<double(const Eigen::Vector3d&)>& f,
                                          const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, double rel_tol, double abs_tol,
                                          int max_leaves = 200000);

}  // namespace bemshape::testing
