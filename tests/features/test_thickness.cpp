// Thickness functions against the closed forms of tests/support/closed_forms.hpp: the plate
// (exact for both measures), the rod and the ball.
#include <catch2/catch.hpp>

#include "features/thickness.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
namespace ref = bemshape::testing;

TEST_CASE("plate: paper and principal thickness are exact") {
  const ref::PdeParameters p{0.3, 0.2};
  for (double h : {0.05, 0.3, 1.0, 5.0}) {
    const double slope = ref::plate_slope(p, h);
    const double f_h = features::inverse_thickness(slope, p.h0);
    CHECK(features::paper_thickness(f_h, p.h0, p.a) == Approx(h).epsilon(1e-12));
    CHECK(features::principal_thickness(slope, p.h0, p.a) == Approx(h).epsilon(1e-12));
  }
}

TEST_CASE("rod: principal thickness ≈ D + 0.5·a·h0, paper thickness ≈ D/2") {
  const ref::PdeParameters p{0.3, 0.2};
  const double radius = 0.3, A = ref::rod_slope(p, radius);
  const double h_p = features::principal_thickness(A, p.h0, p.a);
  const double h_f = features::paper_thickness(features::inverse_thickness(2.0 * A, p.h0), p.h0, p.a);
  CHECK(h_p == Approx(0.632).margin(5e-4));
  CHECK(h_f == Approx(0.286).margin(5e-4));
  // For κR ≫ 1, K0/K1 → 1 − 1/(2κR), so h_p → 2R + a·h0/2.
  const double big = 3.0, A_big = ref::rod_slope(p, big);
  CHECK(features::principal_thickness(A_big, p.h0, p.a) ==
        Approx(2 * big + 0.5 * p.a * p.h0).epsilon(1e-4));
}

TEST_CASE("ball: principal thickness approaches D + a·h0") {
  const ref::PdeParameters p{0.3, 0.2};
  for (double radius : {5.0, 50.0}) {
    const double A = ref::ball_solution(p, radius).A;
    // A = 1/(ã(2 + z + 1/(1+z))) gives h_p = 2R + a·h0 + O(a·h0/z).
    CHECK(features::principal_thickness(A, p.h0, p.a) ==
          Approx(2 * radius + p.a * p.h0).epsilon(0.02 / radius));
  }
}

TEST_CASE("degenerate inverse thickness saturates instead of producing Inf or NaN") {
  for (double f : {0.0, -1.0, 1e-9}) {
    const double h = features::paper_thickness(f, 0.3, 0.2);
    CHECK(std::isfinite(h));
    CHECK(h == Approx(features::kMaxThicknessFactor * 0.3));
  }
  CHECK(features::paper_thickness(10.0, 0.3, 0.2) == 0.0);  // f_h > 1/a: clamped at 0
}
