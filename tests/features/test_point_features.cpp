#include <catch2/catch.hpp>
#include <cmath>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "features/point_features.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
namespace ref = bemshape::testing;

namespace {
features::FeatureParameters params(double w = 0.01) {
  features::FeatureParameters p;
  p.h0 = 0.3;
  p.a = 0.2;
  p.skeleton_width = w;
  return p;
}
}  // namespace

TEST_CASE("plate profile: thickness exact, orientation across the wall, skeleton at the middle") {
  // 1-D plate solution across z ∈ [0, h]: s = (0, 0, c3·(z − h/2)), ∇s = c3·e_z⊗e_z.
  const ref::PdeParameters rp{0.3, 0.2};
  const double h = 0.4, c3 = ref::plate_slope(rp, h);
  const int n = 41;
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(n, 3), g = Eigen::MatrixXd::Zero(n, 9);
  std::vector<char> inside(n, 1);
  for (int k = 0; k < n; ++k) {
    const double z = h * k / (n - 1);
    s(k, 2) = c3 * (z - 0.5 * h);
    g(k, 8) = c3;
  }
  const auto f = features::compute_features<3>(s, g, inside, params(0.011));
  for (int k = 0; k < n; ++k) {
    const double z = h * k / (n - 1);
    CHECK(f.h_f(k) == Approx(h).epsilon(1e-12));
    CHECK(f.h_p(k) == Approx(h).epsilon(1e-12));
    CHECK(std::abs(f.across(k, 2)) == Approx(1.0));
    CHECK(f.skeleton[k] == (std::abs(z - 0.5 * h) <= 0.011 ? 1 : 0));
    if (k != (n - 1) / 2) CHECK(f.n_f(k, 2) == (z > 0.5 * h ? 1.0 : -1.0));
  }
  // At the mid-surface s = 0: no direction, a zero vector rather than NaN.
  CHECK(f.n_f.row((n - 1) / 2).isZero());
}

TEST_CASE("ball closed form: f_h, h_f and h_p from s = A·x") {
  const ref::PdeParameters rp{0.3, 0.2};
  const auto ball = ref::ball_solution(rp, 0.5);
  Eigen::MatrixXd s(1, 3), g(1, 9);
  s << 0.1 * ball.A, -0.2 * ball.A, 0.05 * ball.A;
  g.setZero();
  g(0, 0) = g(0, 4) = g(0, 8) = ball.A;
  const auto f = features::compute_features<3>(s, g, {1}, params());
  CHECK(f.f_h(0) == Approx(0.801142).epsilon(1e-6));
  CHECK(f.h_f(0) == Approx(rp.h0 * (1.0 / 0.801142 - rp.a)).epsilon(1e-5));
  CHECK(f.h_p(0) == Approx(ref::principal_thickness(rp, ball.A)).epsilon(1e-12));
  CHECK(f.n_f.row(0).norm() == Approx(1.0));
}

TEST_CASE("points outside the solid carry zero thickness and no skeleton, but an orientation") {
  Eigen::MatrixXd s(1, 3), g = Eigen::MatrixXd::Identity(3, 3).reshaped(1, 9);
  s << 0.0, 0.0, 0.0;
  const auto f = features::compute_features<3>(s, g, {0}, params(1.0));
  CHECK(f.f_h(0) == 0.0);
  CHECK(f.h_p(0) == 0.0);
  CHECK(f.skeleton[0] == 0);
}

TEST_CASE("features are invariant under rotation of s and ∇s") {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
  Eigen::Matrix3d grad;
  grad << 3.0, 0.2, 0.0, 0.1, 1.5, 0.3, 0.0, 0.2, 0.7;
  const Eigen::Vector3d sv(0.01, 0.02, -0.03);
  Eigen::MatrixXd s1(1, 3), g1(1, 9), s2(1, 3), g2(1, 9);
  s1.row(0) = sv.transpose();
  s2.row(0) = (r * sv).transpose();
  const Eigen::Matrix3d grad2 = r * grad * r.transpose();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      g1(0, 3 * i + j) = grad(i, j);
      g2(0, 3 * i + j) = grad2(i, j);
    }
  const auto a = features::compute_features<3>(s1, g1, {1}, params());
  const auto b = features::compute_features<3>(s2, g2, {1}, params());
  CHECK(a.f_h(0) == Approx(b.f_h(0)).epsilon(1e-12));
  CHECK(a.h_p(0) == Approx(b.h_p(0)).epsilon(1e-12));
  CHECK((r * a.n_f.row(0).transpose() - b.n_f.row(0).transpose()).norm() < 1e-12);
}

TEST_CASE("2-D features: bar of thickness h, tangential orientation is n_f rotated") {
  const ref::PdeParameters rp{0.3, 0.2};
  const double h = 0.35, c3 = ref::plate_slope(rp, h);
  Eigen::MatrixXd s(1, 2), g = Eigen::MatrixXd::Zero(1, 4);
  s << 0.0, 0.05;
  g(0, 3) = c3;
  const auto f = features::compute_features<2>(s, g, {1}, params());
  CHECK(f.h_f(0) == Approx(h).epsilon(1e-12));
  CHECK(f.h_p(0) == Approx(h).epsilon(1e-12));
  CHECK(f.t_f(0, 0) == Approx(-1.0));
  CHECK(f.n_f.row(0).dot(f.t_f.row(0)) == Approx(0.0).margin(1e-15));
}

TEST_CASE("a non-finite solution is a numerical error, mismatched shapes an internal one") {
  Eigen::MatrixXd s(1, 3), g = Eigen::MatrixXd::Zero(1, 9);
  s << std::nan(""), 0.0, 0.0;
  CHECK_THROWS_AS(features::compute_features<3>(s, g, {1}, params()), NumericalError);
  CHECK_THROWS_AS(features::compute_features<3>(s, g, {1, 0}, params()), InternalError);
  auto bad = params();
  bad.h0 = -1.0;
  s(0, 0) = 0.0;
  CHECK_THROWS_AS(features::compute_features<3>(s, g, {1}, bad), InputError);
}
