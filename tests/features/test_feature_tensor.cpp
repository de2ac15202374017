#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "features/feature_tensor.hpp"

using namespace bemshape::features;

TEST_CASE("feature tensor is the symmetric part with ascending eigenpairs") {
  Eigen::Matrix3d g;
  g << 1, 2, 0,  //
      0, 3, 0,   //
      0, 0, -1;
  const auto t = feature_tensor<3>(g);
  CHECK(t.tensor.isApprox(0.5 * (g + g.transpose())));
  CHECK(t.eigenvalues(0) <= t.eigenvalues(1));
  CHECK(t.eigenvalues(1) <= t.eigenvalues(2));
  for (int k = 0; k < 3; ++k) {
    CHECK((t.tensor * t.eigenvectors.col(k) - t.eigenvalues(k) * t.eigenvectors.col(k)).norm() <
          1e-12);
    CHECK(t.eigenvectors.col(k).norm() == Approx(1.0));
  }
  CHECK(t.eigenvalues.sum() == Approx(g.trace()));
}

TEST_CASE("eigenvector signs are fixed: largest component positive") {
  const Eigen::Matrix3d g = Eigen::Vector3d(-1.0, -2.0, -3.0).asDiagonal();
  const auto t = feature_tensor<3>(g);
  for (int k = 0; k < 3; ++k) {
    Eigen::Index i;
    t.eigenvectors.col(k).cwiseAbs().maxCoeff(&i);
    CHECK(t.eigenvectors(i, k) > 0.0);
  }
}

TEST_CASE("eigenvalues are invariant and eigenvectors rotate under a rotation") {
  Eigen::Matrix3d g;
  g << 2.0, 0.3, 0.1, 0.2, 1.0, -0.4, 0.0, 0.5, 0.5;
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto a = feature_tensor<3>(g);
  const auto b = feature_tensor<3>(Eigen::Matrix3d(r * g * r.transpose()));
  CHECK((a.eigenvalues - b.eigenvalues).norm() < 1e-12);
  for (int k = 0; k < 3; ++k)
    CHECK(std::abs((r * a.eigenvectors.col(k)).dot(b.eigenvectors.col(k))) ==
          Approx(1.0).epsilon(1e-12));
}
