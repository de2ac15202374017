#include "tests/bem/adaptive_triangle_reference.hpp"

#include <cmath>
#include <queue>
#include <vector>

#include <Eigen/Geometry>

#include "bem/quadrature/triangle_quadrature.hpp"

namespace bemshape::testing {
namespace {

struct Leaf {
  Eigen::Vector3d a, b, c;
  double refined = 0;  // Σ over the four children
  double error = 0;
  bool operator<(const Leaf& o) const { return error < o.error; }
};

double rule_integral(const std::function<double(const Eigen::Vector3d&)>& f,
                     const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const bem::TriangleRule& rule = bem::collapsed_gauss_rule(12);
  const double area = 0.5 * (b - a).cross(c - a).norm();
  double s = 0;
  for (int q = 0; q < rule.size(); ++q) {
    const auto k = static_cast<size_t>(q);
    s += rule.weight[k] * f(a + rule.xi[k] * (b - a) + rule.eta[k] * (c - a));
  }
  return area * s;
}

Leaf make_leaf(const std::function<double(const Eigen::Vector3d&)>& f, const Eigen::Vector3d& a,
               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  Leaf leaf{a, b, c, 0, 0};
  const double whole = rule_integral(f, a, b, c);
  leaf.refined = rule_integral(f, a, ab, ca) + rule_integral(f, ab, b, bc) +
                 rule_integral(f, ca, bc, c) + rule_integral(f, ab, bc, ca);
  leaf.error = std::abs(whole - leaf.refined);
  return leaf;
}

}  // namespace

AdaptiveResult adaptive_triangle_integral(const std::function<double(const Eigen::Vector3d&)>& f,
                                          const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, double rel_tol, double abs_tol,
                                          int max_leaves) {
  std::priority_queue<Leaf> leaves;
  leaves.push(make_leaf(f, a, b, c));
  double total = leaves.top().refined, error = leaves.top().error;
  while (error > std::max(rel_tol * std::abs(total), abs_tol) &&
         static_cast<int>(leaves.size()) < max_leaves) {
    const Leaf worst = leaves.top();
    leaves.pop();
    total -= worst.refined;
    error -= worst.error;
    const Eigen::Vector3d ab = 0.5 * (worst.a + worst.b), bc = 0.5 * (worst.b + worst.c),
                          ca = 0.5 * (worst.c + worst.a);
    for (const Leaf& child : {make_leaf(f, worst.a, ab, ca), make_leaf(f, ab, worst.b, bc),
                              make_leaf(f, ca, bc, worst.c), make_leaf(f, ab, bc, ca)}) {
      total += child.refined;
      error += child.error;
      leaves.push(child);
    }
  }
  // Recompute the sums to remove the drift of the running updates.
  total = 0;
  error = 0;
  AdaptiveResult result;
  result.leaves = static_cast<int>(leaves.size());
  while (!leaves.empty()) {
    total += leaves.top().refined;
    error += leaves.top().error;
    leaves.pop();
  }
  result.value = total;
  result.error_estimate = error;
  return result;
}

}  // namespace bemshape::testing
