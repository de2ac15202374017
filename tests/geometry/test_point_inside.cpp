#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "geometry/point_inside.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

TEST_CASE("inside a box exactly when inside the closed form, on its faces on the boundary") {
  const Eigen::Vector3d lo(-1, -0.5, 0), hi(1, 0.5, 2);
  const PointInsideQuery query(make_box(lo, hi, 0.3));
  Eigen::MatrixX3d points(0, 3);
  std::vector<Side> expected;
  // A lattice offset so that no point lies on a face.
  for (double x = -1.55; x < 1.6; x += 0.1)
    for (double y = -0.73; y < 0.8; y += 0.1)
      for (double z = -0.33; z < 2.4; z += 0.2) {
        points.conservativeResize(points.rows() + 1, 3);
        points.row(points.rows() - 1) << x, y, z;
        const bool in =
            x > lo.x() && x < hi.x() && y > lo.y() && y < hi.y() && z > lo.z() && z < hi.z();
        expected.push_back(in ? Side::inside : Side::outside);
      }
  const std::vector<Side> sides = query.sides(points);
  REQUIRE(sides.size() == expected.size());
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < sides.size(); ++i)
    wrong += sides[i] != expected[i];
  CHECK(wrong == 0);
  CHECK(query.side(Eigen::Vector3d(0.3, 0.5, 1.0)) == Side::on_boundary);
  CHECK(query.side(hi) == Side::on_boundary);
}

TEST_CASE("a point in the cavity of a spherical shell is outside the solid") {
  const PointInsideQuery query(make_spherical_shell(1.0, 2.0, 6, 8));
  CHECK(query.side(Eigen::Vector3d::Zero()) == Side::outside);
  CHECK(query.side(Eigen::Vector3d(0.5, 0.2, 0.1)) == Side::outside);
  CHECK(query.side(Eigen::Vector3d(1.5, 0, 0)) == Side::inside);
  CHECK(query.side(Eigen::Vector3d(0, -1.2, 0.9)) == Side::inside);
  CHECK(query.side(Eigen::Vector3d(0, 0, 2.5)) == Side::outside);
}

TEST_CASE("an open mesh cannot answer inside/outside") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1.0);
  const SurfaceMesh open(box.vertices(), box.faces().topRows(box.num_faces() - 1));
  CHECK_THROWS_AS(PointInsideQuery(open), InputError);
}
