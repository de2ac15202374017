#include <catch2/catch.hpp>

#include "geometry/closest_point.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape::geometry;

TEST_CASE("closest point on a box: distance, face and barycentric reconstruction") {
  const Eigen::Vector3d lo(0, 0, 0), hi(2, 1, 1);
  const SurfaceMesh box = make_box(lo, hi, 0.25);
  const ClosestPointQuery query(box);

  // Above the top face: the foot is straight below, at distance z − 1.
  const ClosestPoint top = query.closest(Eigen::Vector3d(0.3, 0.6, 1.7));
  CHECK(top.distance == Approx(0.7));
  CHECK(top.point.isApprox(Eigen::Vector3d(0.3, 0.6, 1.0)));
  CHECK(box.face_normals().row(top.face).isApprox(Eigen::RowVector3d(0, 0, 1)));
  // Beyond a corner: the corner itself.
  const ClosestPoint corner = query.closest(Eigen::Vector3d(3, 2, 2));
  CHECK(corner.distance == Approx(std::sqrt(3.0)));
  CHECK(corner.point.isApprox(hi));
  // Inside, nearest to the face x = 0.
  const ClosestPoint inner = query.closest(Eigen::Vector3d(0.1, 0.5, 0.5));
  CHECK(inner.distance == Approx(0.1));

  for (const ClosestPoint& c : {top, corner, inner}) {
    CHECK(c.barycentric.minCoeff() >= 0.0);
    CHECK(c.barycentric.sum() == Approx(1.0));
    const Eigen::Vector3d rebuilt = c.barycentric(0) * box.corner(c.face, 0) +
                                    c.barycentric(1) * box.corner(c.face, 1) +
                                    c.barycentric(2) * box.corner(c.face, 2);
    CHECK((rebuilt - c.point).norm() < 1e-14);
  }
}

TEST_CASE("closest points on a sphere, batch equals single queries") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 8);
  const ClosestPointQuery query(sphere);
  Eigen::MatrixX3d points(200, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double t = 0.37 * static_cast<double>(i), u = 0.11 * static_cast<double>(i);
    const double r = 0.5 + 0.01 * static_cast<double>(i);  // inside and outside
    points.row(i) << r * std::cos(t) * std::sin(u + 0.1), r * std::sin(t) * std::sin(u + 0.1),
        r * std::cos(u + 0.1);
  }
  const ClosestPoints batch = query.closest_points(points);
  // The faceted sphere lies between the inscribed radius and 1.
  const double inscribed = sphere.face_centroids().rowwise().norm().minCoeff();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double r = points.row(i).norm();
    CHECK(batch.distances(i) <= std::abs(r - inscribed) + (1.0 - inscribed) + 1e-12);
    CHECK(batch.distances(i) >= std::max(0.0, std::max(inscribed - r, r - 1.0)) - 1e-12);
    const ClosestPoint single = query.closest(Eigen::Vector3d(points.row(i)));
    CHECK(batch.faces(i) == single.face);
    CHECK(batch.distances(i) == single.distance);
  }
  // Vertices of the mesh are their own closest points.
  const ClosestPoints own = query.closest_points(sphere.vertices());
  CHECK(own.distances.maxCoeff() < 1e-14);
}
