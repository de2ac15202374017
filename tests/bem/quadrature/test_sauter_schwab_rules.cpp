// The Sauter–Schwab rules for touching triangles: exact for polynomials on T̂ × T̂ (which
// checks the sub-domain maps and their Jacobians), and with the direction of x − y in closed
// form for polynomials of x̂ − ŷ; the closed-form moments equal their integrals; the touching
// Galerkin entries they give converge to the same values as the rules with the radial
// direction alone in closed form and as the slow subdivided reference.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/gauss_legendre.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/radial_moments.hpp"
#include "bem/quadrature/sauter_schwab_rules.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape::bem;

namespace {

/// ∫_{T̂} t1^a t2^b dt = 1/((b + 1)(a + b + 2)) on T̂ = {0 ≤ t2 ≤ t1 ≤ 1}.
double monomial_integral(int a, int b) { return 1.0 / ((b + 1.0) * (a + b + 2.0)); }

const TouchingKind kKinds[] = {TouchingKind::coincident, TouchingKind::common_edge,
                               TouchingKind::common_vertex};

}  // namespace

TEST_CASE("Sauter-Schwab rules integrate polynomials on the pair of reference triangles exactly") {
  for (const TouchingKind kind : kKinds) {
    const SauterSchwabRule& rule = sauter_schwab_rule(kind, 5, 1);
    CHECK(rule.size() == (kind == TouchingKind::coincident ? 6 : kind == TouchingKind::common_edge ? 5 : 2) * 125);
    for (int a = 0; a <= 2; ++a)
      for (int b = 0; b <= 2 - a; ++b)
        for (int c = 0; c <= 2; ++c)
          for (int d = 0; d <= 2 - c; ++d) {
            // The nodes are at ξ = 1 and the maps linear in ξ: a monomial of degree D has the
            // radial integral ∫_0^1 ξ³ ξ^D dξ = 1/(D + 4).
            const double radial = 1.0 / (a + b + c + d + 4.0);
            double sum = 0.0;
            for (int q = 0; q < rule.size(); ++q) {
              const auto i = static_cast<size_t>(q);
              sum += rule.weight[i] * radial * std::pow(rule.x1[i], a) * std::pow(rule.x2[i], b) *
                     std::pow(rule.y1[i], c) * std::pow(rule.y2[i], d);
            }
            INFO("kind " << int(kind) << " monomial x1^" << a << " x2^" << b << " y1^" << c << " y2^" << d);
            CHECK(sum == Approx(monomial_integral(a, b) * monomial_integral(c, d)).epsilon(1e-12));
          }
  }
}

TEST_CASE("with x - y in closed form the rules integrate polynomials of the difference exactly") {
  // In the coincident maps x̂ − ŷ, in the edge maps (x̂1 − ŷ1, x̂2, ŷ2) scale with the m
  // leading variables, so a polynomial F of degree D in them has
  // ∫∫ F = Σ_q w_q F(node_q) ∫_0^1 w_m(u) u^D du, with ∫ w_m u^D = 1/(D + 4), 1/((D + 3)(D + 4)),
  // 1/((D + 2)(D + 3)(D + 4)) for m = 1, 2, 3. Reference: the m = 1 rule, exact for
  // polynomials (above).
  const auto moment = [](int m, int degree) {
    const double d = degree;
    return m == 1 ? 1.0 / (d + 4.0) : m == 2 ? 1.0 / ((d + 3.0) * (d + 4.0)) : 1.0 / ((d + 2.0) * (d + 3.0) * (d + 4.0));
  };
  for (const TouchingKind kind : {TouchingKind::coincident, TouchingKind::common_edge}) {
    // The variables that scale: a = x̂1 − ŷ1 and b = x̂2 − ŷ2 (coincident) or a = x̂1 − ŷ1,
    // b = x̂2, c = ŷ2 (edge).
    const auto integrate = [&](const SauterSchwabRule& rule, int i, int j, int k) {
      double sum = 0.0;
      for (int q = 0; q < rule.size(); ++q) {
        const auto p = static_cast<size_t>(q);
        const double a = rule.x1[p] - rule.y1[p];
        const double b = kind == TouchingKind::coincident ? rule.x2[p] - rule.y2[p] : rule.x2[p];
        const double c = kind == TouchingKind::coincident ? 1.0 : rule.y2[p];
        sum += rule.weight[p] * std::pow(a, i) * std::pow(b, j) * std::pow(c, k);
      }
      return sum * moment(rule.closed_form_variables, i + j + k);
    };
    for (int m = 2; m <= max_closed_form_variables(kind); ++m) {
      const SauterSchwabRule& rule = sauter_schwab_rule(kind, 5, m);
      CHECK(rule.closed_form_variables == m);
      CHECK(rule.size() == (kind == TouchingKind::coincident ? 6 : 5) * (m == 2 ? 25 : 5));
      for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3 - i; ++j)
          for (int k = 0; k <= (kind == TouchingKind::coincident ? 0 : 3 - i - j); ++k) {
            INFO("kind " << int(kind) << ", m " << m << ", powers " << i << " " << j << " " << k);
            CHECK(integrate(rule, i, j, k) ==
                  Approx(integrate(sauter_schwab_rule(kind, 5, 1), i, j, k)).epsilon(1e-12).margin(1e-15));
          }
    }
  }
  // A vertex rule cannot leave more than ξ to the closed form, nor an edge rule η2.
  CHECK_THROWS_AS(sauter_schwab_rule(TouchingKind::common_vertex, 5, 2), bemshape::InternalError);
  CHECK_THROWS_AS(sauter_schwab_rule(TouchingKind::common_edge, 5, 3), bemshape::InternalError);
}

TEST_CASE("closed-form moments equal their integrals on both sides of the series threshold") {
  // M_V = ∫ w_m(u) u^{−1} e^{−cu} du and M_K = ∫ w_m(u) u^{−2} (1 + cu) e^{−cu} du by a
  // 40-point Gauss rule (exact to rounding for these entire integrands at c ≤ 40), against
  // yukawa_radial_moments, for w_1 = u³, w_2 = u²(1 − u), w_3 = u(1 − u)²/2.
  const auto& gl = gauss_legendre(40);
  Eigen::ArrayXd c(9);
  c << 1e-6, 0.01, 0.3, 0.999, 1.0, 1.001, 3.0, 12.0, 40.0;
  for (int m = 1; m <= 3; ++m) {
    Eigen::ArrayXd single, double_layer;
    yukawa_radial_moments(m, c, single, m < 3 ? &double_layer : nullptr);
    for (Eigen::Index i = 0; i < c.size(); ++i) {
      double reference_single = 0.0, reference_double = 0.0;
      for (size_t q = 0; q < gl.nodes.size(); ++q) {
        const double u = 0.5 * (1.0 + gl.nodes[q]), w = 0.5 * gl.weights[q];
        const double weight = m == 1 ? u * u * u : m == 2 ? u * u * (1.0 - u) : 0.5 * u * (1.0 - u) * (1.0 - u);
        reference_single += w * weight / u * std::exp(-c(i) * u);
        reference_double += w * weight / (u * u) * (1.0 + c(i) * u) * std::exp(-c(i) * u);
      }
      INFO("m = " << m << ", c = " << c(i));
      CHECK(single(i) == Approx(reference_single).epsilon(1e-14));
      if (m < 3) CHECK(double_layer(i) == Approx(reference_double).epsilon(1e-14));
    }
    // The Laplace limits.
    CHECK(single(0) == Approx(laplace_radial_moments(m).single).epsilon(1e-6));
    if (m < 3) CHECK(double_layer(0) == Approx(laplace_radial_moments(m).double_layer).epsilon(1e-6));
    // M_V alone, for the pairs whose double layer vanishes: the same values, bit for bit.
    Eigen::ArrayXd single_only;
    yukawa_radial_moments(m, c, single_only, static_cast<Eigen::ArrayXd*>(nullptr));
    CHECK((single_only == single).all());
  }
}

TEST_CASE("coplanar touching panels: K exactly 0 and V as the general loop gives it") {
  // Two triangles sharing the edge (0,0,0)–(1,0,0), the second folded down by an angle α
  // about that edge. At α = 0 they are coplanar (V alone is summed, K set to 0); at α = 1e−9
  // the general loop runs, and its V may differ from the coplanar one only by O(α²).
  auto pair = [](double alpha) {
    const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0);
    const Eigen::Vector3d c(0.3, 0.8, 0);
    const Eigen::Vector3d d(0.6, -0.7 * std::cos(alpha), -0.7 * std::sin(alpha));
    return std::vector<Panel>{make_panel(a, b, c), make_panel(b, a, d)};
  };
  for (const double kappa : {0.0, 1.0, 30.0}) {
    const std::vector<Panel> flat = pair(0.0), folded = pair(1e-9);
    struct Entries {
      double single_layer, double_layer, double_layer_transposed;
    };
    auto entries = [&](const std::vector<Panel>& panels) {
      const TouchingOrder order = *touching_order(panels[0], panels[1]);
      const SauterSchwabRule& rule = sauter_schwab_rule(order.kind, 8);
      if (kappa == 0.0) {
        const auto e = GalerkinOperators<LaplaceKernel>(LaplaceKernel{}, panels)
                           .touching_pair(panels[0], panels[1], order, rule);
        return Entries{e.single_layer, e.double_layer, e.double_layer_transposed};
      }
      const auto e = GalerkinOperators<YukawaKernel>(YukawaKernel{kappa}, panels)
                         .touching_pair(panels[0], panels[1], order, rule);
      return Entries{e.single_layer, e.double_layer, e.double_layer_transposed};
    };
    const auto coplanar = entries(flat), general = entries(folded);
    INFO("kappa " << kappa);
    CHECK(coplanar.double_layer == 0.0);
    CHECK(coplanar.double_layer_transposed == 0.0);
    CHECK(std::abs(general.double_layer) > 0.0);  // the folded pair took the general loop
    CHECK(std::abs(general.double_layer) < 1e-6 * std::abs(general.single_layer));
    CHECK(coplanar.single_layer == Approx(general.single_layer).epsilon(1e-12));
  }
}

TEST_CASE("Sauter-Schwab rules put every node inside the reference triangle") {
  for (const TouchingKind kind : kKinds)
    for (int m = 1; m <= max_closed_form_variables(kind); ++m) {
      const SauterSchwabRule& rule = sauter_schwab_rule(kind, 4, m);
      for (int q = 0; q < rule.size(); ++q) {
        const auto i = static_cast<size_t>(q);
        CHECK(rule.weight[i] > 0.0);
        CHECK((0.0 <= rule.x2[i] && rule.x2[i] <= rule.x1[i] && rule.x1[i] <= 1.0));
        CHECK((0.0 <= rule.y2[i] && rule.y2[i] <= rule.y1[i] && rule.y1[i] <= 1.0));
      }
    }
}

TEST_CASE("Sauter-Schwab rules of one point per direction put it at the midpoint") {
  // n = 1: the Gauss variables at 1/2, only the closed-form ones at 1. Vertex region 0 maps
  // x̂ = (ξ, ξη1); edge region 0 x̂ = (ξ, ξη1η3), with η1 in closed form for m = 2.
  CHECK(sauter_schwab_rule(TouchingKind::common_vertex, 1, 1).x2[0] == 0.5);
  CHECK(sauter_schwab_rule(TouchingKind::common_edge, 1, 1).x2[0] == 0.25);
  CHECK(sauter_schwab_rule(TouchingKind::common_edge, 1, 2).x2[0] == 0.5);
}

TEST_CASE("touching_order puts the shared corners first in both panels") {
  const Eigen::Vector3d p(0, 0, 0), q(1, 0, 0), r(0, 1, 0), s(1, 1, 0.4), t(-1, -0.5, 0.2);
  const Panel a = make_panel(p, q, r);
  const Panel edge = make_panel(q, p, t);  // shares p and q, opposite orientation
  const Panel vertex = make_panel(s, t, q);
  const Panel same = make_panel(r, p, q);  // the same triangle, corners rotated
  const auto e = touching_order(a, edge);
  REQUIRE(e);
  CHECK(e->kind == TouchingKind::common_edge);
  for (int i = 0; i < 2; ++i)
    CHECK(a.corners[size_t(e->test[size_t(i)])] == edge.corners[size_t(e->trial[size_t(i)])]);
  const auto v = touching_order(a, vertex);
  REQUIRE(v);
  CHECK(v->kind == TouchingKind::common_vertex);
  CHECK(a.corners[size_t(v->test[0])] == vertex.corners[size_t(v->trial[0])]);
  const auto c = touching_order(a, same);
  REQUIRE(c);
  CHECK(c->kind == TouchingKind::coincident);
  for (int i = 0; i < 3; ++i)
    CHECK(a.corners[size_t(c->test[size_t(i)])] == same.corners[size_t(c->trial[size_t(i)])]);
  CHECK_FALSE(touching_order(a, make_panel(Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(6, 5, 5),
                                           Eigen::Vector3d(5, 6, 5))));
}

namespace {

/// Panel 0 of `panels` with itself and with one edge and one vertex neighbour, tilted against
/// it where the mesh has such neighbours, in both orders.
std::vector<std::pair<size_t, size_t>> touching_pairs(const std::vector<Panel>& panels) {
  std::vector<std::pair<size_t, size_t>> pairs{{0, 0}};
  long edge = -1, vertex = -1;
  for (size_t k = 1; k < panels.size(); ++k) {
    const auto o = touching_order(panels[0], panels[k]);
    if (!o) continue;
    const bool tilted = std::abs(panels[0].normal.dot(panels[k].normal)) < 0.9999;
    if (o->kind == TouchingKind::common_edge && (edge < 0 || tilted)) edge = long(k);
    if (o->kind == TouchingKind::common_vertex && (vertex < 0 || tilted)) vertex = long(k);
  }
  REQUIRE((edge > 0 && vertex > 0));
  pairs.emplace_back(0, size_t(edge));
  pairs.emplace_back(0, size_t(vertex));
  // The reversed pairs: entry() takes their double layer from the pass oriented by face
  // number, i.e. the transposed factor (y − x)·n_j of the (0, k) pass.
  pairs.emplace_back(size_t(edge), 0);
  pairs.emplace_back(size_t(vertex), 0);
  return pairs;
}

/// Errors against the row's scale: |ΔV|/|V_jj| and |ΔK|·diameter/|V_jj|, V_jj the test
/// panel's own entry. An entry's error perturbs the product with a density in proportion to
/// the row, whose largest entry is V_jj, not to the entry's own size (a vertex neighbour's V
/// is 1e−2 to 1e−4 of V_jj).
struct EntryError {
  double single_layer, double_layer;
};

template <class Entry>
EntryError error(const Entry& e, const Entry& reference, double diagonal, double diameter) {
  return {std::abs(e.single_layer - reference.single_layer) / std::abs(diagonal),
          std::abs(e.double_layer - reference.double_layer) * diameter / std::abs(diagonal)};
}

/// V_jj of panel j by the 16-point coincident rule.
template <class Operators>
double diagonal_entry(const Operators& op, const Panel& panel) {
  return op.touching_entry(panel, panel, *touching_order(panel, panel), sauter_schwab_rule(TouchingKind::coincident, 16))
      .single_layer;
}

/// The limit the production rules are checked against: 16 points with the radial direction
/// alone in closed form (m = 1), which does not use the edge and coincident maps' product
/// structure, up to κ·diameter 12; beyond, where its angular points no longer resolve
/// e^{−κr} along x − y to 1e−8 (14 and 16 points differ by 1.4e−8 at 40), the rule of the
/// production m with 16 points.
constexpr double kRadialLimitUpTo = 12.0;

}  // namespace

/// Calls visit(mesh_name, κ·diameter, operators, panels) for a geodesic sphere (panels meeting
/// at small angles) and a box (right-angled edges and corners), with the Laplace kernel
/// (κ·diameter 0) and the Yukawa kernel at κ·diameter 1, 3, 6, 12, 40 and 100 (diameter of
/// panel 0).
template <class Visit>
void for_each_kernel_and_mesh(const Visit& visit) {
  const char* names[] = {"sphere", "box"};
  int m = 0;
  for (const auto& mesh : {bemshape::geometry::make_geodesic_sphere(0.5, 8),
                           bemshape::geometry::make_box(Eigen::Vector3d(0, 0, 0),
                                                        Eigen::Vector3d(1, 0.5, 0.3), 0.2)}) {
    const auto panels = make_panels(mesh);
    const double diameter = panels[0].diameter;
    for (const double kd : {0.0, 1.0, 3.0, 6.0, 12.0, 40.0, 100.0}) {
      if (kd == 0.0)
        visit(names[m], kd, GalerkinOperators(LaplaceKernel{}, panels), panels);
      else
        visit(names[m], kd, GalerkinOperators(YukawaKernel{kd / diameter}, panels), panels);
    }
    ++m;
  }
}

TEST_CASE("touching Galerkin entries converge and the production rules are within 1e-7 of the row") {
  for_each_kernel_and_mesh([](const char*, double kd, const auto& op, const std::vector<Panel>& panels) {
    const double diameter = panels[0].diameter;
    for (const auto& [j, k] : touching_pairs(panels)) {
      const Panel& test = panels[j];
      const Panel& trial = panels[k];
      const TouchingOrder order = *touching_order(test, trial);
      const int limit_m = kd <= kRadialLimitUpTo ? 1 : max_closed_form_variables(order.kind);
      const double diagonal = diagonal_entry(op, test);
      const auto limit = op.touching_entry(test, trial, order, sauter_schwab_rule(order.kind, 16, limit_m));
      const auto next = op.touching_entry(test, trial, order, sauter_schwab_rule(order.kind, 14, limit_m));
      const EntryError converged = error(next, limit, diagonal, diameter);
      const auto production = op.entry(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k));
      const EntryError e = error(production, limit, diagonal, diameter);
      INFO("kappa*diameter " << kd << ", kind " << int(order.kind) << ": V error " << e.single_layer
                             << ", K error " << e.double_layer);
      CHECK(converged.single_layer < 1e-8);  // 14 and 16 points agree: the limit is converged
      CHECK(converged.double_layer < 1e-8);
      CHECK(e.single_layer < 1e-7);
      CHECK(e.double_layer < 2e-6);
      // The closed form along x − y and the radial one agree where both converge.
      if (kd <= kRadialLimitUpTo && order.kind != TouchingKind::common_vertex) {
        const auto collapsed = op.touching_entry(test, trial, order, sauter_schwab_rule(order.kind, 16));
        const EntryError agree = error(collapsed, limit, diagonal, diameter);
        CHECK(agree.single_layer < 1e-8);
        CHECK(agree.double_layer < 1e-8);
      }
      // An independent scheme (a subdivided outer rule × the exact radial inner integral)
      // approaches the same limit as its outer rule is refined. Checked in the forward order
      // only and up to κ·diameter 12: the reversed pairs are there for the production entries
      // above (at κ·diameter = 12 the slow scheme's 3 levels do not reach 5e−3 for the
      // reversed vertex pair, nor beyond for the others).
      if (j > k || kd > kRadialLimitUpTo) continue;
      const auto coarse = op.outer_rule_entry(test, trial, 1, symmetric_triangle_rule(4));
      const auto fine = op.outer_rule_entry(test, trial, 3, symmetric_triangle_rule(4));
      const double pair = std::abs(limit.single_layer);
      const EntryError coarse_error = error(coarse, limit, pair, diameter);
      const EntryError fine_error = error(fine, limit, pair, diameter);
      CHECK(fine_error.single_layer < 5e-3);
      CHECK(fine_error.single_layer < coarse_error.single_layer / 4.0);
      if (order.kind != TouchingKind::coincident) {
        CHECK(fine_error.double_layer < 5e-3);
        CHECK(fine_error.double_layer < coarse_error.double_layer / 4.0);
      }
    }
  });
}

// Prints the table of docs/quadrature.md ("Touching panels"): the production rules' errors
// against the limit, beside those of the rule of the same n with the radial direction alone in
// closed form, both relative to the row's diagonal entry.
//   build/tests/bem/test_bem "touching entry errors by kappa*diameter"
TEST_CASE("touching entry errors by kappa*diameter", "[.calibration]") {
  for_each_kernel_and_mesh([](const char* mesh, double kd, const auto& op, const std::vector<Panel>& panels) {
    const double diameter = panels[0].diameter;
    for (const auto& [j, k] : touching_pairs(panels)) {
      const TouchingOrder order = *touching_order(panels[j], panels[k]);
      const int limit_m = kd <= kRadialLimitUpTo ? 1 : max_closed_form_variables(order.kind);
      const double diagonal = diagonal_entry(op, panels[j]);
      const auto limit = op.touching_entry(panels[j], panels[k], order, sauter_schwab_rule(order.kind, 16, limit_m));
      const EntryError e = error(op.entry(Eigen::Index(j), Eigen::Index(k)), limit, diagonal, diameter);
      const int n = touching_rule_points(order.kind);
      const auto radial = op.touching_entry(panels[j], panels[k], order, sauter_schwab_rule(order.kind, n, 1));
      const EntryError r = error(radial, limit, diagonal, diameter);
      std::printf("| %s | %5.1f | %s%s | %d | %.1e | %.1e | %.1e | %.1e | %.1e |\n", mesh, kd,
                  order.kind == TouchingKind::coincident    ? "coincident"
                  : order.kind == TouchingKind::common_edge ? "edge"
                                                            : "vertex",
                  j > k ? " (reversed)" : "", n, std::abs(limit.single_layer / diagonal), e.single_layer,
                  e.double_layer, r.single_layer, r.double_layer);
    }
  });
}
