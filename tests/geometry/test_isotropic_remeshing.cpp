#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/isotropic_remeshing.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

/// Closed, consistently oriented, no degenerate faces, outward.
void require_valid_solid(const SurfaceMesh& mesh) {
  const MeshValidation v = validate_mesh(mesh.vertices(), mesh.faces());
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
  CHECK(!v.zero_area_faces);
  CHECK(!v.collapsed_faces);
  CHECK(mesh.signed_volume() > 0.0);
}

/// Largest distance from a vertex of `mesh` to the surface `reference`.
double max_distance_to(const SurfaceMesh& mesh, const SurfaceMesh& reference) {
  return ClosestPointQuery(reference).closest_points(mesh.vertices()).distances.maxCoeff();
}

}  // namespace

TEST_CASE("box: closed, edges bounded, geometry and sharp edges kept exactly") {
  const Eigen::Vector3d lo(-1, 0, 0.5), hi(2, 1, 1.5);
  const SurfaceMesh coarse = make_box(lo, hi, 3.0);  // two triangles per side
  const double h = 0.1;
  const SurfaceMesh fine = refine_to_edge_length(coarse, h);
  require_valid_solid(fine);
  CHECK(fine.max_edge_length() <= 1.3 * h);
  CHECK(fine.mean_edge_length() == Approx(h).epsilon(0.15));
  CHECK(fine.signed_volume() == Approx(3.0).epsilon(1e-12));
  CHECK(fine.area() == Approx(2 * (3.0 + 3.0 + 1.0)).epsilon(1e-12));
  CHECK(max_distance_to(fine, coarse) < 1e-12);
  CHECK(fine.bounding_box().min.isApprox(lo));
  CHECK(fine.bounding_box().max.isApprox(hi));

  // Each of the 12 box edges is covered by mesh edges lying exactly on it.
  const Eigen::MatrixX3d& v = fine.vertices();
  auto on_box_edge = [&](Eigen::Index i, int axis) {
    int extreme = 0;
    for (int k = 0; k < 3; ++k)
      if (k != axis && (v(i, k) == lo(k) || v(i, k) == hi(k)))
        ++extreme;
    return extreme == 2;
  };
  for (int axis = 0; axis < 3; ++axis) {
    double covered = 0.0;
    for (Eigen::Index f = 0; f < fine.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Index a = fine.faces()(f, k), b = fine.faces()(f, (k + 1) % 3);
        bool same_line = on_box_edge(a, axis) && on_box_edge(b, axis);
        for (int j = 0; j < 3 && same_line; ++j)
          if (j != axis)
            same_line = v(a, j) == v(b, j);
        if (same_line)
          covered += 0.5 * (v.row(a) - v.row(b)).norm();  // each edge twice
      }
    CHECK(covered == Approx(4.0 * (hi(axis) - lo(axis))).epsilon(1e-12));
  }
}

TEST_CASE("sphere: every facet crease is kept by default, so volume and area are exact") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 6);
  const double h = 0.08;
  const SurfaceMesh fine = refine_to_edge_length(sphere, h);
  require_valid_solid(fine);
  CHECK(fine.max_edge_length() <= 1.3 * h);
  CHECK(max_distance_to(fine, sphere) < 1e-12);
  CHECK(fine.signed_volume() == Approx(sphere.signed_volume()).epsilon(1e-12));
  CHECK(fine.area() == Approx(sphere.area()).epsilon(1e-12));
}

TEST_CASE("sphere with a large feature angle: remeshed across facets, points still on them") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 6);
  const double h = 0.08;
  RemeshingOptions options;
  options.sharp_angle_degrees = 30.0;  // no edge of the sphere is sharp
  const SurfaceMesh fine = refine_to_edge_length(sphere, h, options);
  require_valid_solid(fine);
  CHECK(fine.max_edge_length() <= 1.3 * h);
  CHECK(max_distance_to(fine, sphere) < 1e-12);
  // Chords between points of the faceted input cut below it: a small loss, never a gain.
  CHECK(fine.signed_volume() <= sphere.signed_volume());
  CHECK(fine.signed_volume() == Approx(sphere.signed_volume()).epsilon(5e-3));
  CHECK(fine.area() == Approx(sphere.area()).epsilon(5e-3));
}

TEST_CASE("plate_holes slivers become a closed mesh within the edge bound") {
  const PreparedMesh plate = prepare_mesh_file(data + "/meshes/plate_holes.STL");
  REQUIRE(plate.mesh.max_edge_length() > 200.0);
  const double h = 6.0;
  const SurfaceMesh fine = refine_to_edge_length(plate.mesh, h);
  require_valid_solid(fine);
  CHECK(fine.max_edge_length() <= 1.3 * h);
  CHECK(!validate_mesh(fine.vertices(), fine.faces()).needle_faces);
  CHECK(max_distance_to(fine, plate.mesh) < 1e-9 * plate.mesh.bounding_box().diagonal());
  CHECK(fine.signed_volume() == Approx(plate.mesh.signed_volume()).epsilon(1e-12));
  CHECK(fine.area() == Approx(plate.mesh.area()).epsilon(1e-12));
  // The input's vertices are all on the output too: the surfaces coincide.
  CHECK(max_distance_to(plate.mesh, fine) < 1e-9 * plate.mesh.bounding_box().diagonal());
  CHECK(fine.bounding_box().extent().isApprox(plate.mesh.bounding_box().extent(), 1e-12));
}

TEST_CASE("a mesh already as fine as the target and well shaped is kept as it is") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 16);
  const double longest = sphere.max_edge_length();
  CHECK(fine_enough(sphere, longest));
  const SurfaceMesh kept = refine_to_edge_length(sphere, longest);
  CHECK(kept.vertices() == sphere.vertices());
  CHECK(kept.faces() == sphere.faces());
  // A smaller target remeshes; so does a much larger one (the sphere has more than three times
  // the faces it asks for), and so does plate_holes at any size (slivers below 20°).
  CHECK_FALSE(fine_enough(sphere, 0.99 * longest));
  CHECK(refine_to_edge_length(sphere, 0.7 * longest).num_faces() > sphere.num_faces());
  CHECK_FALSE(fine_enough(sphere, 3.0 * longest));
  // Up to kKeepInputFaceRatio (3) times the faces the target asks for, area/(√3/4·h²), the
  // input is kept: at 2.5 times (the 81,920-face sphere at its default edge asks for 2.54
  // times fewer) it is, at 3.5 times it is not.
  const auto target_for_face_ratio = [&](double ratio) {
    return std::sqrt(ratio * sphere.area() / (kEquilateralArea * double(sphere.num_faces())));
  };
  REQUIRE(target_for_face_ratio(2.5) >= longest);
  CHECK(fine_enough(sphere, target_for_face_ratio(2.5)));
  CHECK_FALSE(fine_enough(sphere, target_for_face_ratio(3.5)));
  const PreparedMesh plate = prepare_mesh_file(data + "/meshes/plate_holes.STL");
  CHECK_FALSE(fine_enough(plate.mesh, 1000.0));
}

TEST_CASE("remeshing refuses nonsense targets and runaway sizes") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1.0);
  CHECK_THROWS_AS(refine_to_edge_length(box, 0.0), InputError);
  CHECK_THROWS_AS(refine_to_edge_length(box, -1.0), InputError);
  CHECK_THROWS_AS(refine_to_edge_length(box, std::nan("")), InputError);
  CHECK_THROWS_AS(refine_to_edge_length(box, 1e-5), ResourceError);
  const SurfaceMesh open(box.vertices(), box.faces().topRows(box.num_faces() - 1));
  CHECK_THROWS_AS(refine_to_edge_length(open, 0.2), InputError);
}
