#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/surface_mesh.hpp"  // concatenated, with_flipped_orientation

using namespace bemshape;
using namespace bemshape::geometry;

namespace {
/// Area of the regular polygon of `segments` corners inscribed in a circle of radius r.
double polygon_area(double r, int segments) {
  return 0.5 * segments * r * r * std::sin(2.0 * std::numbers::pi / segments);
}

/// The mesh passes the input pipeline untouched: closed, manifold, outward, no
/// self-intersection, and nothing to repair.
void require_clean_solid(const SurfaceMesh& mesh) {
  TriangleSoup soup;
  soup.vertices = mesh.vertices();
  soup.faces = mesh.faces();
  const PreparedMesh prepared = inspect_triangle_soup(soup, "constructed solid");
  INFO(prepared.report.refusal_message());
  REQUIRE(prepared.report.usable());
  CHECK(prepared.report.shells >= 1);
}
}  // namespace

TEST_CASE("extruded polygons: volume = area × height, closed and outward, any simple polygon") {
  Polygon2 l(6, 2);  // an L: not convex, so ear clipping must skip the reflex corner
  l << 0, 0, 60, 0, 60, 3, 3, 3, 3, 40, 0, 40;
  const SurfaceMesh prism = extrude_polygon(l, -1.0, 49.0);
  CHECK(prism.signed_volume() == Approx((60 * 3 + 3 * 37) * 50.0).epsilon(1e-12));
  CHECK(prism.area() == Approx(2 * (60 * 3 + 3 * 37) + 2 * (60 + 40) * 50.0).epsilon(1e-12));
  require_clean_solid(prism);

  const SurfaceMesh cylinder = make_faceted_cylinder({1, 2}, 5.0, 0.0, 10.0, 48);
  CHECK(cylinder.signed_volume() == Approx(polygon_area(5.0, 48) * 10.0).epsilon(1e-12));
  require_clean_solid(cylinder);

  Polygon2 clockwise = l.colwise().reverse();
  CHECK_THROWS_AS(extrude_polygon(clockwise, 0, 1), InputError);
  CHECK_THROWS_AS(extrude_polygon(l, 1, 1), InputError);
}

TEST_CASE("Booleans: a box minus a cylinder and a box plus a box have the volumes of the sets") {
  const SurfaceMesh box = make_box_solid({0, 0, 0}, {20, 10, 4});
  const SurfaceMesh hole = make_faceted_cylinder({10, 5}, 3.0, -1.0, 5.0, 32);
  const SurfaceMesh plate = mesh_difference(box, hole);
  CHECK(plate.signed_volume() == Approx(800.0 - polygon_area(3.0, 32) * 4.0).epsilon(1e-10));
  require_clean_solid(plate);

  // Overlapping boxes sharing the bottom plane (coplanar faces, exact coordinates).
  const SurfaceMesh tab = make_box_solid({19, 3, 0}, {30, 7, 2});
  const SurfaceMesh joined = mesh_union(box, tab);
  CHECK(joined.signed_volume() == Approx(800.0 + 10 * 4 * 2).epsilon(1e-10));
  require_clean_solid(joined);

  Eigen::Affine3d motion = Eigen::Affine3d::Identity();
  motion.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  motion.translate(Eigen::Vector3d(5, -2, 7));
  CHECK(transformed(joined, motion).signed_volume() == Approx(joined.signed_volume()).epsilon(1e-12));
}

TEST_CASE("Booleans refuse an operand that crosses itself or does not bound a volume") {
  // CGAL's corefinement assumes both and read outside its arrays without them
  // (docs/reliability.md, "Fuzzing"): the operands are checked first.
  const SurfaceMesh box = make_box_solid({0, 0, 0}, {2, 2, 2});
  const SurfaceMesh other = make_box_solid({1, 1, 1}, {3, 3, 3});
  const SurfaceMesh crossing = concatenated(box, other);  // closed, manifold, crosses itself
  CHECK_THROWS_WITH(mesh_union(box, crossing),
                    Catch::Contains("second operand intersects itself"));
  CHECK_THROWS_WITH(mesh_difference(crossing, box),
                    Catch::Contains("first operand intersects itself"));
  // Closed, manifold, free of crossings, but a shell inside another faces the same way:
  // no volume has these faces as its boundary. Facing the other way, the pair bounds a
  // hollow box.
  const SurfaceMesh inner = make_box_solid({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5});
  CHECK_THROWS_WITH(mesh_union(concatenated(box, inner), other),
                    Catch::Contains("first operand does not bound a volume"));
  const SurfaceMesh hollow = concatenated(box, with_flipped_orientation(inner));
  // |box ∪ other| = 15, less the cavity's part outside `other` (1 − 0.5³).
  CHECK(mesh_union(hollow, other).signed_volume() ==
        Approx(15.0 - (1.0 - 0.125)).epsilon(1e-10));
  // Disjoint shells in one operand are fine: the union holds both volumes.
  const SurfaceMesh apart = concatenated(box, make_box_solid({5, 0, 0}, {6, 1, 1}));
  CHECK(mesh_union(apart, other).signed_volume() == Approx(8.0 + 1.0 + 8.0 - 1.0).epsilon(1e-10));
}
