#include "bem/quadrature/sauter_schwab_rules.hpp"

#include <array>
#include <mutex>
#include <string>

#include "bem/quadrature/gauss_legendre.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

constexpr int kMaxPoints = 16;

/// One sub-domain: its map from (ξ, η1, η2, η3) ∈ [0, 1]⁴ to (x̂, ŷ), with the Jacobian.
struct Point4 {
  double x1, x2, y1, y2, jacobian;
};

/// Coincident triangles: six sub-domains, Jacobian ξ³η1²η2.
Point4 coincident(int region, double xi, double e1, double e2, double e3) {
  const double j = xi * xi * xi * e1 * e1 * e2;
  switch (region) {
    case 0: return {xi, xi * (1 - e1 + e1 * e2), xi * (1 - e1 * e2 * e3), xi * (1 - e1), j};
    case 1: return {xi * (1 - e1 * e2 * e3), xi * (1 - e1), xi, xi * (1 - e1 + e1 * e2), j};
    case 2: return {xi, xi * e1 * (1 - e2 + e2 * e3), xi * (1 - e1 * e2), xi * e1 * (1 - e2), j};
    case 3: return {xi * (1 - e1 * e2), xi * e1 * (1 - e2), xi, xi * e1 * (1 - e2 + e2 * e3), j};
    case 4: return {xi * (1 - e1 * e2 * e3), xi * e1 * (1 - e2 * e3), xi, xi * e1 * (1 - e2), j};
    default: return {xi, xi * e1 * (1 - e2), xi * (1 - e1 * e2 * e3), xi * e1 * (1 - e2 * e3), j};
  }
}

/// A common edge {t2 = 0}: five sub-domains, Jacobian ξ³η1² (first) or ξ³η1²η2.
Point4 common_edge(int region, double xi, double e1, double e2, double e3) {
  const double j = xi * xi * xi * e1 * e1;
  switch (region) {
    case 0: return {xi, xi * e1 * e3, xi * (1 - e1 * e2), xi * e1 * (1 - e2), j};
    case 1: return {xi, xi * e1, xi * (1 - e1 * e2 * e3), xi * e1 * e2 * (1 - e3), j * e2};
    case 2: return {xi * (1 - e1 * e2), xi * e1 * (1 - e2), xi, xi * e1 * e2 * e3, j * e2};
    case 3: return {xi * (1 - e1 * e2 * e3), xi * e1 * e2 * (1 - e3), xi, xi * e1, j * e2};
    default: return {xi * (1 - e1 * e2 * e3), xi * e1 * (1 - e2 * e3), xi, xi * e1 * e2, j * e2};
  }
}

/// A common vertex t = 0: two sub-domains (which of the two points is farther from the
/// vertex in the t1 direction), Jacobian ξ³η2.
Point4 common_vertex(int region, double xi, double e1, double e2, double e3) {
  const double j = xi * xi * xi * e2;
  if (region == 0) return {xi, xi * e1, xi * e2, xi * e2 * e3, j};
  return {xi * e2, xi * e2 * e3, xi, xi * e1, j};
}

SauterSchwabRule make_rule(TouchingKind kind, int n, int m) {
  const GaussLegendreRule& gl = gauss_legendre(n);
  std::vector<double> t(static_cast<size_t>(n)), w(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    t[size_t(i)] = 0.5 * (1.0 + gl.nodes[size_t(i)]);
    w[size_t(i)] = 0.5 * gl.weights[size_t(i)];
  }
  const int regions = kind == TouchingKind::coincident ? 6 : kind == TouchingKind::common_edge ? 5 : 2;
  // The m leading variables of (ξ, η1, η2, η3) are at 1 (the caller integrates them); the
  // others run over the Gauss points, a single point of weight 1 standing for a fixed one.
  const bool fixed1 = m >= 2, fixed2 = m >= 3;  // η1, η2 at 1
  const int n1 = fixed1 ? 1 : n, n2 = fixed2 ? 1 : n;
  SauterSchwabRule rule;
  rule.closed_form_variables = m;
  const size_t size = size_t(regions) * size_t(n1) * size_t(n2) * size_t(n);
  for (auto* v : {&rule.x1, &rule.x2, &rule.y1, &rule.y2, &rule.weight}) v->reserve(size);
  for (int region = 0; region < regions; ++region)
    for (int b = 0; b < n1; ++b)
      for (int c = 0; c < n2; ++c)
        for (int d = 0; d < n; ++d) {
          const double e1 = fixed1 ? 1.0 : t[size_t(b)], e2 = fixed2 ? 1.0 : t[size_t(c)];
          const double e3 = t[size_t(d)];
          const double weight =
              (fixed1 ? 1.0 : w[size_t(b)]) * (fixed2 ? 1.0 : w[size_t(c)]) * w[size_t(d)];
          const Point4 p = kind == TouchingKind::coincident ? coincident(region, 1.0, e1, e2, e3)
                           : kind == TouchingKind::common_edge
                               ? common_edge(region, 1.0, e1, e2, e3)
                               : common_vertex(region, 1.0, e1, e2, e3);
          rule.x1.push_back(p.x1);
          rule.x2.push_back(p.x2);
          rule.y1.push_back(p.y1);
          rule.y2.push_back(p.y2);
          // The Jacobian at the node: its factors in the leading variables are 1 there, so
          // what is left are those in the Gauss variables.
          rule.weight.push_back(p.jacobian * weight);
        }
  return rule;
}

}  // namespace

const SauterSchwabRule& sauter_schwab_rule(TouchingKind kind, int n, int m) {
  if (n < 1 || n > kMaxPoints)
    throw InternalError("sauter_schwab_rule: n = " + std::to_string(n) + " outside [1, " +
                        std::to_string(kMaxPoints) + "]");
  if (m < 1 || m > max_closed_form_variables(kind))
    throw InternalError("sauter_schwab_rule: " + std::to_string(m) +
                        " variables in closed form, the maps of this kind allow 1 to " +
                        std::to_string(max_closed_form_variables(kind)));
  static std::array<std::array<std::array<SauterSchwabRule, kMaxPoints + 1>, 3>, 3> rules;
  static std::array<std::array<std::array<std::once_flag, kMaxPoints + 1>, 3>, 3> built;
  const auto k = static_cast<size_t>(kind), v = static_cast<size_t>(m - 1);
  std::call_once(built[k][v][size_t(n)], [&] { rules[k][v][size_t(n)] = make_rule(kind, n, m); });
  return rules[k][v][size_t(n)];
}

}  // namespace bemshape::bem
