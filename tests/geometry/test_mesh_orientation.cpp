#include <catch2/catch.hpp>
#include <numbers>

#include "geometry/mesh_orientation.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape::geometry;

namespace {

Eigen::MatrixX3i flip_faces(Eigen::MatrixX3i f, std::initializer_list<Eigen::Index> which) {
  for (Eigen::Index i : which)
    std::swap(f(i, 1), f(i, 2));
  return f;
}

}  // namespace

TEST_CASE("reversed faces are turned back, the smaller side is flipped") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 4);
  const Eigen::MatrixX3i f = flip_faces(sphere.faces(), {3, 50, 51, 200});
  const ConsistentOrientation c = orient_consistently(sphere.vertices(), f);
  CHECK(c.orientable);
  CHECK(c.faces_flipped == 4);
  CHECK(c.faces == sphere.faces());
  CHECK(!validate_mesh(sphere.vertices(), c.faces).inconsistent_edges);
}

TEST_CASE("an inside-out shell is reversed to enclose positive volume") {
  const SurfaceMesh sphere = make_geodesic_sphere(2.0, 5);
  const SurfaceMesh inverted = with_flipped_orientation(sphere);
  const VolumeOrientation o = orient_to_bound_volume(inverted.vertices(), inverted.faces());
  CHECK(o.shells_flipped == 1);
  CHECK(o.faces_flipped == static_cast<std::size_t>(sphere.num_faces()));
  CHECK(o.faces == sphere.faces());
  CHECK(o.cavities == 0);
}

TEST_CASE("a cavity wall is oriented into the cavity, an island inside it outward") {
  const double r1 = 1.0, r2 = 2.0, r3 = 0.5;
  // All three spheres outward: the middle one (a cavity wall, depth 1) must be reversed;
  // the island (depth 2) and the skin (depth 0) stay.
  const SurfaceMesh all_out =
      concatenated(concatenated(make_geodesic_sphere(r2, 6), make_geodesic_sphere(r1, 5)),
                   make_geodesic_sphere(r3, 4));
  const VolumeOrientation o = orient_to_bound_volume(all_out.vertices(), all_out.faces());
  REQUIRE(o.shells.size() == 3);
  CHECK(o.shells[0].depth == 0);
  CHECK(o.shells[1].depth == 1);
  CHECK(o.shells[2].depth == 2);
  CHECK(!o.shells[0].flipped);
  CHECK(o.shells[1].flipped);
  CHECK(!o.shells[2].flipped);
  CHECK(o.cavities == 1);
  CHECK(o.shells[1].volume < 0.0);
  const SurfaceMesh fixed(all_out.vertices(), o.faces);
  const double inscribed_error = 0.05;  // faceted spheres enclose slightly less
  CHECK(fixed.signed_volume() ==
        Approx(4.0 / 3.0 * std::numbers::pi * (r2 * r2 * r2 - r1 * r1 * r1 + r3 * r3 * r3))
            .epsilon(inscribed_error));

  // The primitive shell is already right: nothing changes.
  const SurfaceMesh shell = make_spherical_shell(r1, r2, 4, 6);
  const VolumeOrientation ok = orient_to_bound_volume(shell.vertices(), shell.faces());
  CHECK(ok.shells_flipped == 0);
  CHECK(ok.cavities == 1);
}
