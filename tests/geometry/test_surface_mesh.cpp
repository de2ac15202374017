#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "geometry/surface_mesh.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

TEST_CASE("face normals, areas and centroids of a single triangle") {
  Eigen::MatrixX3d v(3, 3);
  v << 0, 0, 0, 2, 0, 0, 0, 1, 0;
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  const SurfaceMesh mesh(v, f);
  CHECK(mesh.face_areas()(0) == Approx(1.0));
  CHECK(mesh.face_normals().row(0).isApprox(Eigen::RowVector3d(0, 0, 1)));
  CHECK(mesh.face_centroids().row(0).isApprox(Eigen::RowVector3d(2.0 / 3.0, 1.0 / 3.0, 0)));
  CHECK(mesh.max_edge_length() == Approx(std::sqrt(5.0)));
}

TEST_CASE("a zero-area face gets a zero normal instead of NaN") {
  Eigen::MatrixX3d v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  const SurfaceMesh mesh(v, f);
  CHECK(mesh.face_areas()(0) == 0.0);
  CHECK(mesh.face_normals().row(0).isZero());
}

TEST_CASE("invalid indices and non-finite coordinates are input errors") {
  Eigen::MatrixX3d v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 3;
  CHECK_THROWS_AS(SurfaceMesh(v, f), InputError);
  f << 0, 1, 2;
  v(1, 1) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(SurfaceMesh(v, f), InputError);
}
