#include <catch2/catch.hpp>

#include "tests/support/surface_distance.hpp"

using bemshape::testing::max_distance_to_surface;
using bemshape::testing::triangle_distance;

TEST_CASE("triangle distance: the face, edge and corner regions of a right triangle") {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  CHECK(triangle_distance({0.5, 0.5, 3.0}, a, b, c) == Approx(3.0));   // above the face
  CHECK(triangle_distance({1.0, -1.0, 1.0}, a, b, c) == Approx(std::sqrt(2.0)));  // edge ab
  CHECK(triangle_distance({2.0, 2.0, 0.0}, a, b, c) == Approx(std::sqrt(2.0)));   // edge bc
  CHECK(triangle_distance({-3.0, -4.0, 0.0}, a, b, c) == Approx(5.0));  // corner a
  CHECK(triangle_distance({4.0, 0.0, 0.0}, a, b, c) == Approx(2.0));   // corner b
}

TEST_CASE("triangle distance: a point on a sliver is at distance 0 to rounding") {
  // 200 long, 1e-6 high: barycentric coordinates would lose ten digits here.
  const Eigen::Vector3d a(0, 0, 0), b(200, 0, 0), c(100, 1e-6, 0);
  CHECK(triangle_distance({72.5, 2e-7, 0.0}, a, b, c) <= 1e-15);
  const Eigen::MatrixX3d points = Eigen::RowVector3d(72.5, 2e-7, 0.0);
  Eigen::MatrixX3d vertices(3, 3);
  vertices << a.transpose(), b.transpose(), c.transpose();
  const Eigen::MatrixX3i faces = Eigen::RowVector3i(0, 1, 2);
  CHECK(max_distance_to_surface(points, vertices, faces) <= 1e-15);
}
