#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "bem/kernels/laplace_kernel.hpp"

using bemshape::bem::LaplaceKernel;

TEST_CASE("Laplace kernel: value and radial derivatives of 1/(4 pi r)", "[laplace_kernel]") {
  const LaplaceKernel G{};
  CHECK(G.kappa() == 0.0);
  CHECK_FALSE(LaplaceKernel::has_exponential_decay);
  for (double r : {1e-3, 0.1, 1.0, 7.5}) {
    CHECK(G.value(r) == Approx(1.0 / (4.0 * std::numbers::pi * r)).epsilon(1e-15));
    const double h = 1e-5 * r;
    CHECK(G.radial_derivative(r) ==
          Approx((G.value(r + h) - G.value(r - h)) / (2 * h)).epsilon(1e-8));
    CHECK(G.second_radial_derivative(r) ==
          Approx((G.radial_derivative(r + h) - G.radial_derivative(r - h)) / (2 * h)).epsilon(1e-8));
    // Harmonic away from the source: G'' + 2G'/r = 0.
    CHECK(std::abs(G.second_radial_derivative(r) + 2.0 * G.radial_derivative(r) / r) <
          1e-14 * G.second_radial_derivative(r));
  }
}

TEST_CASE("Laplace kernel: gradient is -(x - y)/(4 pi r^3)", "[laplace_kernel]") {
  const LaplaceKernel G{};
  const Eigen::Vector3d x(0.3, -0.2, 1.1), y(-0.4, 0.5, 0.2);
  const double r = (x - y).norm();
  const Eigen::Vector3d expected = -(x - y) / (4.0 * std::numbers::pi * r * r * r);
  CHECK((G.gradient(x, y) - expected).norm() < 1e-15 * expected.norm());
}

TEST_CASE("Laplace kernel: flux of the gradient through a sphere is -1", "[laplace_kernel]") {
  // ∮ ∇_x G · n_x dA over |x − y| = ρ equals −1 for every ρ (Gauss's law, −ΔG = δ).
  const LaplaceKernel G{};
  const double rho = 0.7;
  const Eigen::Vector3d y(0.1, 0.2, 0.3);
  const Eigen::Vector3d n(0.0, 0.6, 0.8);
  CHECK(G.gradient(y + rho * n, y).dot(n) * 4.0 * std::numbers::pi * rho * rho ==
        Approx(-1.0).epsilon(1e-14));
}
