#include "bem/quadrature/triangle_quadrature.hpp"

#include <array>
#include <string>

#include "bem/quadrature/gauss_legendre.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

/// Largest collapsed rule served from the cache: 32² points reach degree 62, beyond anything a
/// flat-panel integrand needs.
constexpr int max_collapsed_points = 32;

/// Builds a rule from orbits of barycentric coordinates (λ1, λ2, λ3): each orbit lists one
/// representative and the weight of each of its points; the orbit is expanded by permuting
/// the coordinates (1, 3 or 6 distinct points). ξ = λ2, η = λ3.
struct Orbit {
  double l1, l2, l3, weight;
};

TriangleRule expand_orbits(int degree, std::initializer_list<Orbit> orbits) {
  TriangleRule rule;
  rule.degree = degree;
  for (const Orbit& o : orbits) {
    const std::array<std::array<double, 3>, 6> perms = {{{o.l1, o.l2, o.l3},
                                                         {o.l1, o.l3, o.l2},
                                                         {o.l2, o.l1, o.l3},
                                                         {o.l2, o.l3, o.l1},
                                                         {o.l3, o.l1, o.l2},
                                                         {o.l3, o.l2, o.l1}}};
    std::vector<std::array<double, 3>> distinct;
    for (const auto& p : perms) {
      bool seen = false;
      for (const auto& q : distinct) seen = seen || (p == q);
      if (!seen) distinct.push_back(p);
    }
    for (const auto& p : distinct) {
      rule.xi.push_back(p[1]);
      rule.eta.push_back(p[2]);
      rule.weight.push_back(o.weight);
    }
  }
  return rule;
}

/// S21 orbit (a, a, 1 − 2a) and S111 orbit (a, b, 1 − a − b).
Orbit s3(double w) { return {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, w}; }
Orbit s21(double a, double w) { return {a, a, 1.0 - 2.0 * a, w}; }
Orbit s111(double a, double b, double w) { return {a, b, 1.0 - a - b, w}; }

std::vector<TriangleRule> make_symmetric_rules() {
  std::vector<TriangleRule> rules;
  rules.push_back(expand_orbits(1, {s3(1.0)}));
  rules.push_back(expand_orbits(2, {s21(1.0 / 6.0, 1.0 / 3.0)}));
  rules.push_back(expand_orbits(4, {s21(0.445948490915965, 0.223381589678011),
                                    s21(0.091576213509771, 0.109951743655322)}));
  rules.push_back(expand_orbits(5, {s3(0.225), s21(0.470142064105115, 0.132394152788506),
                                    s21(0.101286507323456, 0.125939180544827)}));
  rules.push_back(expand_orbits(6, {s21(0.249286745170910, 0.116786275726379),
                                    s21(0.063089014491502, 0.050844906370207),
                                    s111(0.053145049844817, 0.310352451033784,
                                         0.082851075618374)}));
  rules.push_back(expand_orbits(8, {s3(0.144315607677787),
                                    s21(0.459292588292723, 0.095091634267285),
                                    s21(0.170569307751760, 0.103217370534718),
                                    s21(0.050547228317031, 0.032458497623198),
                                    s111(0.008394777409958, 0.263112829634638,
                                         0.027230314174435)}));
  return rules;
}

TriangleRule make_collapsed_rule(int n) {
  const GaussLegendreRule& gl = gauss_legendre(n);
  TriangleRule rule;
  rule.degree = 2 * n - 2;
  for (int i = 0; i < n; ++i) {
    const double u = 0.5 * (1.0 + gl.nodes[static_cast<size_t>(i)]);
    const double wu = 0.5 * gl.weights[static_cast<size_t>(i)];
    for (int j = 0; j < n; ++j) {
      const double v = 0.5 * (1.0 + gl.nodes[static_cast<size_t>(j)]);
      const double wv = 0.5 * gl.weights[static_cast<size_t>(j)];
      rule.xi.push_back(u);
      rule.eta.push_back((1.0 - u) * v);
      // Jacobian (1 − u) of the collapse, times 2 so that the weights sum to 1 (|T̂| = ½).
      rule.weight.push_back(2.0 * wu * wv * (1.0 - u));
    }
  }
  return rule;
}

}  // namespace

const TriangleRule& symmetric_triangle_rule(int degree) {
  static const std::vector<TriangleRule> rules = make_symmetric_rules();
  for (const TriangleRule& rule : rules)
    if (rule.degree >= degree && degree >= 1) return rule;
  throw InternalError("symmetric_triangle_rule: degree " + std::to_string(degree) +
                      " outside [1, 8]");
}

const TriangleRule& collapsed_gauss_rule(int n) {
  static const std::vector<TriangleRule> rules = [] {
    std::vector<TriangleRule> r(1);
    for (int k = 1; k <= max_collapsed_points; ++k) r.push_back(make_collapsed_rule(k));
    return r;
  }();
  if (n < 1 || n > max_collapsed_points)
    throw InternalError("collapsed_gauss_rule: n = " + std::to_string(n) + " outside [1, " +
                        std::to_string(max_collapsed_points) + "]");
  return rules[static_cast<size_t>(n)];
}

}  // namespace bemshape::bem
