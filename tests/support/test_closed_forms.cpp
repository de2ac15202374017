// The closed-form references themselves are checked against the PDE they claim to solve
// (interface conditions by finite differences) and against the figures quoted in the issues,
// so that a mistake in a reference cannot hide a mistake in a solver.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/support/closed_forms.hpp"

using namespace bemshape::testing;

namespace {
// Central difference of f at x with step δ (second-order accurate).
template <class F>
double derivative(F f, double x, double delta = 1e-6) {
  return (f(x + delta) - f(x - delta)) / (2.0 * delta);
}
}  // namespace

TEST_CASE("ball reference matches the quoted figures and the interface conditions") {
  const PdeParameters p{0.3, 0.2};
  const auto ball = ball_solution(p, 0.5);
  CHECK(ball.A == Approx(2.967193).epsilon(1e-6));
  CHECK(inverse_thickness(p, 3.0 * ball.A) == Approx(0.801142).epsilon(1e-6));
  const double R = 0.5, d = 1e-11;
  CHECK(ball.psi(R - d) == Approx(ball.psi(R + d)).epsilon(1e-6));
  const double inner = ball.A;
  const double outer = derivative([&](double r) { return ball.psi(r); }, R + 1e-4, 1e-6);
  // ψ'_in − ψ'_out = 1/ã (the outer derivative is taken just outside R, hence the tolerance).
  CHECK(inner - outer == Approx(1.0 / p.a_tilde()).epsilon(5e-3));
}

TEST_CASE("shell reference matches the quoted figure and the interface conditions") {
  const PdeParameters p{0.3, 0.2};
  const auto shell = shell_solution(p, 0.7, 1.0);
  CHECK(inverse_thickness(p, 3.0 * shell.A) == Approx(0.851801).epsilon(1e-6));
  for (double R : {0.7, 1.0}) {
    const double eps = 1e-9;
    CHECK(shell.psi(R - eps) == Approx(shell.psi(R + eps)).epsilon(1e-6));
  }
  const double h = 1e-6;
  const double out2 = (shell.psi(1.0 + 2 * h) - shell.psi(1.0 + h)) / h;
  const double cav1 = (shell.psi(0.7 - h) - shell.psi(0.7 - 2 * h)) / h;
  CHECK(shell.dpsi_solid(1.0) - out2 == Approx(1.0 / p.a_tilde()).epsilon(1e-3));
  CHECK(shell.dpsi_solid(0.7) - cav1 == Approx(1.0 / p.a_tilde()).epsilon(1e-3));
}

TEST_CASE("rod reference gives the quoted principal and paper thickness") {
  const PdeParameters p{0.3, 0.2};
  const double A = rod_slope(p, 0.3);
  CHECK(principal_thickness(p, A) == Approx(0.632).margin(5e-4));
  CHECK(paper_thickness(p, inverse_thickness(p, 2.0 * A)) == Approx(0.286).margin(5e-4));
}

TEST_CASE("plate reference recovers the thickness exactly") {
  const PdeParameters p{0.3, 0.2};
  for (double h : {0.1, 0.3, 0.7, 2.0}) {
    CHECK(paper_thickness(p, inverse_thickness(p, plate_slope(p, h))) == Approx(h).epsilon(1e-12));
  }
}

TEST_CASE("the 1-D constants (paper's, two misprints corrected) satisfy its boundary and interface conditions") {
  const PdeParameters p{0.2, 0.2};
  const double K = 0.0, L = 1.0;
  for (double pos : {0.2, 0.4}) {
    for (double h : {0.1, 0.2, 0.3}) {
      const auto sol = interval_1d_solution(p, K, L, pos, h);
      const double scale = h / p.a_tilde();
      CHECK(sol.s(K) == Approx(0.0).margin(1e-12 * scale));
      CHECK(sol.s(L) == Approx(0.0).margin(1e-12 * scale));
      const double d = 1e-9;
      CHECK(sol.s(pos - d) == Approx(sol.s(pos)).margin(1e-6 * scale));
      CHECK(sol.s(pos + h + d) == Approx(sol.s(pos + h)).margin(1e-6 * scale));
      auto s = [&](double x) { return sol.s(x); };
      const double left = derivative(s, pos - 1e-5, 1e-7);
      const double right = derivative(s, pos + h + 1e-5, 1e-7);
      CHECK(sol.c3 - left == Approx(1.0 / p.a_tilde()).epsilon(2e-3));
      CHECK(sol.c3 - right == Approx(1.0 / p.a_tilde()).epsilon(2e-3));
    }
  }
}
