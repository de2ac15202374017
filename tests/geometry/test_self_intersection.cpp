#include <catch2/catch.hpp>
#include <omp.h>

#include "geometry/primitive_meshes.hpp"
#include "geometry/self_intersection.hpp"

using namespace bemshape::geometry;

TEST_CASE("closed primitives and disjoint shells do not self-intersect") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 6);
  CHECK(find_self_intersections(sphere.vertices(), sphere.faces()).pairs == 0);
  const SurfaceMesh shell = make_spherical_shell(1.0, 1.5, 4, 5);
  CHECK(find_self_intersections(shell.vertices(), shell.faces()).pairs == 0);
  const SurfaceMesh apart =
      concatenated(sphere, make_geodesic_sphere(1.0, 3, Eigen::Vector3d(2.01, 0, 0)));
  CHECK(find_self_intersections(apart.vertices(), apart.faces()).pairs == 0);
}

TEST_CASE("overlapping shells intersect, first pair located in the overlap") {
  const SurfaceMesh a = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.5);
  const SurfaceMesh b =
      make_box(Eigen::Vector3d::Constant(0.75), Eigen::Vector3d::Constant(1.75), 0.5);
  const SurfaceMesh both = concatenated(a, b);
  const SelfIntersections r = find_self_intersections(both.vertices(), both.faces());
  CHECK(r.pairs > 0);
  // The first pair's face touches the box where the two overlap: [0.75, 1]^3 grown by one
  // face size (0.5).
  CHECK((r.first.array() >= 0.25).all());
  CHECK((r.first.array() <= 1.5).all());
}

TEST_CASE("a vertex pushed through the opposite side makes the surface cross itself") {
  SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.25);
  Eigen::MatrixX3d v = box.vertices();
  // An interior vertex of the face z = 0 pushed to z = 1.5, through the top face.
  Eigen::Index moved = -1;
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (v(i, 2) == 0.0 && v(i, 0) == 0.5 && v(i, 1) == 0.5)
      moved = i;
  REQUIRE(moved >= 0);
  v(moved, 2) = 1.5;
  CHECK(find_self_intersections(v, box.faces()).pairs > 0);
}

TEST_CASE("the scan in slabs, one per thread, finds each intersecting pair once") {
  // Two spheres of 20,480 faces each (enough for two slabs) crossing on the circle x = 0.25,
  // where the scan's cut across x falls: pairs on both sides of it and straddling it.
  const SurfaceMesh both = concatenated(make_geodesic_sphere(1.0, 32),
                                        make_geodesic_sphere(1.0, 32, Eigen::Vector3d(0.5, 0, 0)));
  REQUIRE(both.num_faces() == 40960);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SelfIntersections one = find_self_intersections(both.vertices(), both.faces());
  omp_set_num_threads(2);
  const SelfIntersections two = find_self_intersections(both.vertices(), both.faces());
  omp_set_num_threads(threads);
  // Each face of the circle's band meets a few faces of the other sphere.
  CHECK(one.pairs > 500);
  CHECK(two.pairs == one.pairs);
  CHECK(two.face_pairs == one.face_pairs);
  CHECK(one.face_pairs.size() == one.pairs);
}
