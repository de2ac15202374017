#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "bem/kernels/yukawa_kernel.hpp"

using bemshape::bem::YukawaKernel;

TEST_CASE("Yukawa kernel: value and radial derivatives of exp(-kr)/(4 pi r)", "[yukawa_kernel]") {
  for (double kappa : {1e-3, 0.5, 3.0, 40.0}) {
    const YukawaKernel G(kappa);
    CHECK(G.kappa() == kappa);
    for (double r : {1e-3, 0.1, 1.0}) {
      INFO("kappa = " << kappa << ", r = " << r);
      CHECK(G.value(r) ==
            Approx(std::exp(-kappa * r) / (4.0 * std::numbers::pi * r)).epsilon(1e-15));
      const double h = 1e-5 * r;
      CHECK(G.radial_derivative(r) ==
            Approx((G.value(r + h) - G.value(r - h)) / (2 * h)).epsilon(1e-7));
      CHECK(G.second_radial_derivative(r) ==
            Approx((G.radial_derivative(r + h) - G.radial_derivative(r - h)) / (2 * h))
                .epsilon(1e-7));
      // (Δ − κ²)G = 0 away from the source: G'' + 2G'/r = κ²G.
      CHECK(G.second_radial_derivative(r) + 2.0 * G.radial_derivative(r) / r ==
            Approx(kappa * kappa * G.value(r)).epsilon(1e-12).margin(1e-14 * G.second_radial_derivative(r)));
    }
  }
}

TEST_CASE("Yukawa kernel: gradient and the cutoff distance", "[yukawa_kernel]") {
  const YukawaKernel G(2.5);
  const Eigen::Vector3d x(0.3, -0.2, 1.1), y(-0.4, 0.5, 0.2);
  const double r = (x - y).norm();
  const Eigen::Vector3d expected = G.radial_derivative(r) * (x - y) / r;
  CHECK((G.gradient(x, y) - expected).norm() < 1e-15 * expected.norm());
  // Beyond the cutoff the kernel is below e^{−40} of its value at r = 1/κ.
  const double rc = G.cutoff_distance();
  CHECK(rc == Approx(40.0 / 2.5));
  CHECK(G.value(rc) < 5e-18 * G.value(1.0 / 2.5));
}

TEST_CASE("Yukawa kernel: kappa must be positive and finite", "[yukawa_kernel]") {
  CHECK_THROWS_AS(YukawaKernel(0.0), bemshape::InputError);
  CHECK_THROWS_AS(YukawaKernel(-1.0), bemshape::InputError);
  CHECK_THROWS_AS(YukawaKernel(std::numeric_limits<double>::quiet_NaN()), bemshape::InputError);
  CHECK_THROWS_AS(YukawaKernel(std::numeric_limits<double>::infinity()), bemshape::InputError);
}
