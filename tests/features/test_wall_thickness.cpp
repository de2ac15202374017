#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "features/wall_thickness.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
using bemshape::testing::PdeParameters;

TEST_CASE("mid-surface thickness: exact on a plate, the diffusion offset removed on a rod and a ball") {
  const PdeParameters p{0.3, 0.2};
  SECTION("plate: S = diag(0, 0, slope)") {
    for (double t : {0.05, 0.3, 1.0, 4.0})
      CHECK(features::mid_surface_thickness({0, 0, testing::plate_slope(p, t)}, p.h0, p.a) ==
            Approx(t).epsilon(1e-12));
  }
  SECTION("rod axis: S = diag(0, A, A); h_p alone reads 2R + a·h0/2") {
    const double radius = 1.0, z = p.kappa() * radius, A = testing::rod_slope(p, radius);
    const double corrected = features::mid_surface_thickness({0, A, A}, p.h0, p.a);
    const double principal = p.h0 * (1.0 / (p.h0 * p.h0 * A) - p.a);
    CHECK(principal - 2 * radius == Approx(0.5 * p.a * p.h0).epsilon(0.05));
    // What is left is of order a·h0/z (3/8 of it, from K0/K1's expansion).
    CHECK(std::abs(corrected - 2 * radius) < 0.5 * p.a * p.h0 / z);
  }
  SECTION("ball centre: S = A·I; h_p alone reads 2R + a·h0(1 + 1/(1+z))") {
    for (double radius : {0.5, 1.0, 3.0}) {
      const double z = p.kappa() * radius, A = testing::ball_solution(p, radius).A;
      CHECK(features::mid_surface_thickness({A, A, A}, p.h0, p.a) ==
            Approx(2 * radius + p.a * p.h0 / (1 + z)).epsilon(1e-12));
    }
  }
}

TEST_CASE("mid-surface thickness of a tube: within 0.15 % of the wall, where twice the depth is off by several %") {
  struct Case { double inner, outer, h0; };
  for (const Case c : {Case{12, 15, 2.7}, Case{12, 15, 1.5}, Case{5, 8, 2.7}, Case{2, 5, 2.7},
                       Case{40, 42, 1.8}}) {
    INFO("tube " << c.inner << " < r < " << c.outer << ", h0 " << c.h0);
    const PdeParameters p{c.h0, 0.2};
    const testing::TubeSolution tube = testing::tube_solution(p, c.inner, c.outer);
    const double rho0 = tube.mid_radius(), wall = c.outer - c.inner;
    REQUIRE(rho0 > c.inner);
    REQUIRE(rho0 < c.outer);
    CHECK(std::abs(tube.psi(rho0)) < 1e-12 * std::abs(tube.psi(c.outer)));
    // On the mid-surface the tangential eigenvalue ψ/ρ vanishes and the axial one is 0.
    const double h_mid = features::mid_surface_thickness({0, 0, tube.dpsi_solid(rho0)}, p.h0, p.a);
    CHECK(h_mid == Approx(wall).epsilon(1.5e-3));
    // The mid-surface is not the geometric middle: twice its depth from either skin is off by
    // about ±t²H/2 (H = 1/(2R) the mean curvature of the middle cylinder; the Robin condition
    // outside adds to it).
    const double outer_reading = 2 * (c.outer - rho0), inner_reading = 2 * (rho0 - c.inner);
    const double estimate = wall * wall / (2 * (c.inner + c.outer));
    CHECK(outer_reading - wall > 0.5 * estimate);
    CHECK(outer_reading - wall < 1.5 * estimate);
    CHECK(wall - inner_reading > 0.5 * estimate);
    CHECK(wall - inner_reading < 1.5 * estimate);
  }
}

TEST_CASE("wall thickness: the mid-surface reading inside a wall, the skins' separation near a rim") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using features::wall_thickness;
  CHECK(wall_thickness(4.0, nan, 2.0) == 4.0);                         // no mid-surface depth
  CHECK(std::isnan(wall_thickness(4.0, 40.0, 1.0, 4.0)));              // searched along the wall
  CHECK(wall_thickness(4.3, 4.0, 0.05) == 4.3);                        // within a wall
  CHECK(wall_thickness(4.3, 4.0, 0.05, 4.2) == 4.3);                   // within a wall, paired
  CHECK(wall_thickness(5.2, 4.0, features::kRimFull, 4.0) == 4.0);     // at a rim: the pair
  CHECK(wall_thickness(5.2, 4.0, 2 * features::kRimFull, 4.0) == 4.0);
  // At a rim without a pair, neither twice the depth nor h_mid is the wall: the neighbours'.
  CHECK(std::isnan(wall_thickness(5.2, 4.0, features::kRimFull)));
  CHECK(std::isnan(wall_thickness(5.2, 4.0, 0.5 * (features::kRimFrom + features::kRimFull))));
  CHECK(wall_thickness(5.2, 4.0, features::kRimFrom) == 5.2);
  // From h_mid to the pair between kRimFrom and kRimFull (5.2 is within kJunctionRatio of
  // 5.0: no junction).
  double previous = wall_thickness(5.2, 4.0, features::kRimFrom, 5.0);
  CHECK(previous == 5.2);
  for (double r = features::kRimFrom; r <= features::kRimFull; r += 0.01) {
    const double w = wall_thickness(5.2, 4.0, r, 5.0);
    CHECK(w <= previous);
    CHECK(w >= 5.0);
    previous = w;
  }
  CHECK(wall_thickness(5.2, 4.0, features::kRimFull, 5.0) == 5.0);
  // A junction: h_mid more than kJunctionRatio above the pair takes the pair.
  CHECK(wall_thickness(5.2, 4.0, features::kRimFrom, 4.0) == 4.0);
}

TEST_CASE("wall thickness: a search that crosses its wall obliquely has no reading of its own") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using features::wall_thickness;
  // |n·e3| = cos 60°: a face tilted halfway between two walls.
  CHECK(std::isnan(wall_thickness(4.0, 4.0, 0.05, 4.0, 0.5)));
  CHECK(std::isnan(wall_thickness(4.0, 4.0, 0.05, nan, features::kMinAlignment - 1e-3)));
  CHECK(wall_thickness(4.0, 4.0, 0.05, 4.0, features::kMinAlignment + 1e-3) == 4.0);
  CHECK(wall_thickness(4.0, 4.0, 0.05, 4.0, 1.0) == 4.0);
  CHECK(wall_thickness(4.0, 4.0, 0.05, 4.0, nan) == 4.0);  // e3 not defined: a rod, a ball
}

// Each rule of wall_thickness() and each of its constants at its boundary, with literal
// values (not the named constants), so that deleting a rule or moving its constant fails here.
TEST_CASE("wall thickness: every rule and constant at its boundary") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using features::wall_thickness;
  SECTION("along the wall: twice the depth above 1.5·h_mid") {
    CHECK(wall_thickness(4.0, 1.45 * 4.0, 0.05) == 4.0);
    CHECK(std::isnan(wall_thickness(4.0, 1.55 * 4.0, 0.05)));
    CHECK(std::isnan(wall_thickness(4.0, 1.55 * 4.0, 0.05, 4.0, 1.0)));  // a pair does not save it
    CHECK(features::along_wall(2.0, 3.1));
    CHECK(!features::along_wall(2.0, 2.9));
  }
  SECTION("oblique: |n·e3| below cos 30°") {
    CHECK(std::isnan(wall_thickness(4.0, 4.0, 0.05, 4.0, 0.85)));
    CHECK(wall_thickness(4.0, 4.0, 0.05, 4.0, 0.88) == 4.0);
  }
  SECTION("rim blend: h_mid alone up to 0.1, the pair alone from 0.3, linear between") {
    CHECK(wall_thickness(5.0, 4.0, 0.09, 4.9) == 5.0);
    CHECK(wall_thickness(5.0, 4.0, 0.11, 4.9) < 5.0);
    CHECK(wall_thickness(5.0, 4.0, 0.2, 4.9) == Approx(4.95).epsilon(1e-12));
    CHECK(wall_thickness(5.0, 4.0, 0.15, 4.9) == Approx(4.975).epsilon(1e-12));
    CHECK(wall_thickness(5.0, 4.0, 0.29, 4.9) > 4.9);
    CHECK(wall_thickness(5.0, 4.0, 0.31, 4.9) == 4.9);
    CHECK(features::rim_weight(0.1) == 0.0);
    CHECK(features::rim_weight(0.3) == 1.0);
  }
  SECTION("near a rim without a pair: no reading of its own, unless 2τ0 agrees within 2.5 %") {
    CHECK(wall_thickness(5.0, 4.0, 0.09) == 5.0);
    CHECK(std::isnan(wall_thickness(5.0, 4.0, 0.11)));
    CHECK(wall_thickness(4.0, 4.09, 0.2) == 4.0);  // a taper: h_mid
    CHECK(wall_thickness(4.0, 3.91, 0.2) == 4.0);
    CHECK(std::isnan(wall_thickness(4.0, 4.11, 0.2)));
    CHECK(std::isnan(wall_thickness(4.0, 3.89, 0.2)));
  }
  SECTION("junction: h_mid more than 5 % above the pair takes the pair, inside the wall too") {
    CHECK(wall_thickness(4.19, 4.0, 0.0, 4.0) == 4.19);  // 4.75 % above: a ball's centre
    CHECK(wall_thickness(4.21, 4.0, 0.0, 4.0) == 4.0);   // 5.25 % above: a junction
    CHECK(wall_thickness(5.4, 4.0, 0.05, 4.0) == 4.0);   // the foot of a rib: +35 %
    // The cap applies to the blended reading: at weight ½, (5 + 4.5)/2 = 4.75 > 1.05·4.5.
    CHECK(wall_thickness(5.0, 4.0, 0.2, 4.5) == 4.5);
    // h_mid below the pair is never capped.
    CHECK(wall_thickness(3.0, 4.0, 0.0, 4.0) == 3.0);
  }
  SECTION("no mid-surface depth: h_mid, whatever else") {
    CHECK(wall_thickness(4.0, nan, 0.5, 3.0, 0.1) == 4.0);
  }
}
