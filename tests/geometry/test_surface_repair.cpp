// Repairs that change the surface (geometry/surface_repair.hpp, nonmanifold_split.hpp)
// through the whole preparation pipeline, on damaged copies of bundled parts and primitive
// solids built here: every repaired mesh must be closed, manifold, free of
// self-intersections, with its volume within a stated bound of the intact part's, and the
// report must name each repair with its place and size. What is larger than the repair
// length must be refused with the tolerance in the message.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "geometry/mesh_preparation.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/self_intersection.hpp"
#include "geometry/surface_repair.hpp"
#include "geometry/vertex_welding.hpp"
#include "tests/support/damaged_meshes.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

TriangleSoup soup_of(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f) {
  TriangleSoup soup;
  soup.vertices = v;
  soup.faces = f;
  soup.format = "memory";
  return soup;
}

TriangleSoup soup_of(const SurfaceMesh& mesh) { return soup_of(mesh.vertices(), mesh.faces()); }

/// The faces of `f` without those listed.
Eigen::MatrixX3i without(const Eigen::MatrixX3i& f, const std::set<Eigen::Index>& drop) {
  Eigen::MatrixX3i kept(f.rows() - static_cast<Eigen::Index>(drop.size()), 3);
  Eigen::Index row = 0;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (drop.count(i) == 0)
      kept.row(row++) = f.row(i);
  return kept;
}

/// Faces around vertex v.
std::set<Eigen::Index> fan(const Eigen::MatrixX3i& f, int v) {
  std::set<Eigen::Index> faces;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (f(i, 0) == v || f(i, 1) == v || f(i, 2) == v)
      faces.insert(i);
  return faces;
}

double area_of(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
               const std::set<Eigen::Index>& which) {
  double area = 0.0;
  for (Eigen::Index i : which)
    area += 0.5 * (Eigen::Vector3d(v.row(f(i, 1))) - Eigen::Vector3d(v.row(f(i, 0))))
                      .cross(Eigen::Vector3d(v.row(f(i, 2))) - Eigen::Vector3d(v.row(f(i, 0))))
                      .norm();
  return area;
}

/// Bounding-box diagonal of the vertices of the faces listed, without vertex `except`.
double extent_of(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                 const std::set<Eigen::Index>& which, int except = -1) {
  Eigen::AlignedBox3d box;
  for (Eigen::Index i : which)
    for (int k = 0; k < 3; ++k)
      if (f(i, k) != except)
        box.extend(Eigen::Vector3d(v.row(f(i, k))));
  return box.diagonal().norm();
}

bool has_problem(const MeshReport& r, MeshProblem::Status status, const std::string& what) {
  for (const MeshProblem& p : r.problems)
    if (p.status == status && p.what.find(what) != std::string::npos)
      return true;
  return false;
}

bool has_repair(const MeshReport& r, const std::string& text) {
  for (const std::string& line : r.repairs)
    if (line.find(text) != std::string::npos)
      return true;
  return false;
}

/// The promise of a repaired mesh: usable, closed, manifold, consistently oriented, no
/// self-intersection, outward (positive volume).
void check_sound(const PreparedMesh& p) {
  CAPTURE(p.report.refusal_message());
  REQUIRE(p.report.usable());
  const MeshValidation v = validate_mesh(p.mesh.vertices(), p.mesh.faces());
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
  CHECK(!v.collapsed_faces);
  CHECK(!v.duplicate_faces);
  CHECK(find_self_intersections(p.mesh.vertices(), p.mesh.faces()).pairs == 0);
  CHECK(p.mesh.signed_volume() > 0.0);
}

}  // namespace

TEST_CASE("repair: a removed fan on the sphere is refilled close to the sphere") {
  // unit_sphere.STL: radius 1, 1280 faces. Its vertex fans are 0.36 across (10 % of the
  // diagonal, above the default repair length), so the caller passes a length scale, as it
  // would pass h0.
  const TriangleSoup sphere = read_triangle_soup(data + "/meshes/unit_sphere.STL");
  const PreparedMesh intact = prepare_mesh_file(data + "/meshes/unit_sphere.STL");
  const std::set<Eigen::Index> removed = fan(sphere.faces, sphere.faces(100, 0));
  const double d = extent_of(sphere.vertices, sphere.faces, removed, sphere.faces(100, 0));
  MeshPreparationOptions options;
  options.repair_length = 0.5;
  REQUIRE(d < options.repair_length);
  const PreparedMesh p =
      inspect_triangle_soup(soup_of(sphere.vertices, without(sphere.faces, removed)), "sphere",
                            options);
  check_sound(p);
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "1 hole up to"));
  CHECK(has_repair(p.report, "filled a hole of " + std::to_string(removed.size()) + " edges"));
  CHECK(p.report.repair_length == 0.5);
  // The patch spans a rim of diameter about d on a sphere of radius 1: the removed cap and
  // the patch both lie within the sagitta s = 1 − sqrt(1 − (d/2)²) of the rim's plane, so
  // the volumes differ by at most s times the removed area.
  const double s = 1.0 - std::sqrt(1.0 - d * d / 4.0);
  const double bound = s * area_of(sphere.vertices, sphere.faces, removed);
  CAPTURE(d, s, bound, p.report.volume, intact.report.volume);
  CHECK(std::abs(p.report.volume - intact.report.volume) <= bound);
  for (Eigen::Index i = 0; i < p.mesh.num_vertices(); ++i)
    CHECK(std::abs(p.mesh.vertices().row(i).norm() - 1.0) <= s);
}

TEST_CASE("repair: the smallest vertex fan of plate_holes removed is refilled at the default") {
  // plate_holes.STL (a CAD export, 1252 faces): the smallest fan of a vertex lies on the
  // wall of one of the small holes, 7.08 across, under 2 % of the diagonal (7.33).
  const TriangleSoup soup = read_triangle_soup(data + "/meshes/plate_holes.STL");
  const WeldResult w = weld_vertices(soup.vertices, soup.faces);
  const PreparedMesh intact = prepare_mesh_file(data + "/meshes/plate_holes.STL");
  int best = -1;
  double d = 1e300;
  for (int v = 0; v < w.vertices.rows(); ++v) {
    const double e = extent_of(w.vertices, w.faces, fan(w.faces, v), v);
    if (e < d) {
      d = e;
      best = v;
    }
  }
  REQUIRE(d < kRepairRelativeLength * intact.report.bounding_box.diagonal());
  const std::set<Eigen::Index> removed = fan(w.faces, best);
  const PreparedMesh p =
      inspect_triangle_soup(soup_of(w.vertices, without(w.faces, removed)), "plate_holes");
  check_sound(p);
  CHECK(has_repair(p.report, "filled a hole of " + std::to_string(removed.size()) + " edges"));
  // The removed surface and the patch both span the rim, inside a region d across: the
  // volume moves by at most d³ (here 5e-4 of the part).
  CAPTURE(d, p.report.volume, intact.report.volume);
  CHECK(std::abs(p.report.volume - intact.report.volume) <= d * d * d);
}

TEST_CASE("repair: a small hole on a flat face is closed flat, volume unchanged") {
  // A plate whose top face has a fine patch around its centre: removing one vertex's fan
  // leaves a hole 0.14 across on a plate 10 x 10 x 1 (under 2 % of the diagonal, 0.28).
  const SurfaceMesh coarse = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 10, 1), 0.1);
  Eigen::MatrixX3d v = coarse.vertices();
  const Eigen::MatrixX3i& f = coarse.faces();
  int centre = -1;
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (v.row(i).isApprox(Eigen::RowVector3d(5, 5, 1)))
      centre = static_cast<int>(i);
  REQUIRE(centre >= 0);
  const std::set<Eigen::Index> removed = fan(f, centre);
  const double d = extent_of(v, f, removed, centre);
  REQUIRE(d < 0.02 * coarse.bounding_box().diagonal());
  const PreparedMesh p = inspect_triangle_soup(soup_of(v, without(f, removed)), "plate");
  check_sound(p);
  CHECK(p.report.volume == Approx(100.0).epsilon(1e-12));
  CHECK(has_repair(p.report, "filled a hole of"));
  CHECK(has_repair(p.report, "rim flat to 0"));
  CHECK(p.mesh.vertices().col(2).maxCoeff() == 1.0);
}

TEST_CASE("repair: a hole larger than the repair length is refused with the tolerance") {
  const SurfaceMesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.25);
  std::set<Eigen::Index> removed;
  for (Eigen::Index i = 0; i < box.num_faces(); ++i)
    if (box.face_centroids()(i, 2) == 1.0 && box.face_centroids()(i, 0) < 0.5)
      removed.insert(i);
  const PreparedMesh p =
      inspect_triangle_soup(soup_of(box.vertices(), without(box.faces(), removed)), "box");
  CHECK(!p.report.usable());
  CHECK_THAT(p.report.refusal_message(),
             Catch::Contains("open boundary edges (first at ") &&
                 Catch::Contains("1 hole up to 1.12 across, larger than the repair length "
                                 "0.0346 (2 % of the bounding-box diagonal)") &&
                 Catch::Contains("close the holes"));
  MeshPreparationOptions options;
  options.repair_length = 1.5;  // a caller that accepts a hole this large
  const PreparedMesh q =
      inspect_triangle_soup(soup_of(box.vertices(), without(box.faces(), removed)), "box",
                            options);
  check_sound(q);
  CHECK(q.report.volume == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("repair: a duplicated face, either orientation, is dropped") {
  const TriangleSoup sphere = read_triangle_soup(data + "/meshes/unit_sphere.STL");
  const PreparedMesh intact = prepare_mesh_file(data + "/meshes/unit_sphere.STL");
  Eigen::MatrixX3i f(sphere.faces.rows() + 2, 3);
  f.topRows(sphere.faces.rows()) = sphere.faces;
  f.row(sphere.faces.rows()) = sphere.faces.row(7);
  f.row(sphere.faces.rows() + 1) << sphere.faces(30, 0), sphere.faces(30, 2), sphere.faces(30, 1);
  const PreparedMesh p = inspect_triangle_soup(soup_of(sphere.vertices, f), "sphere");
  check_sound(p);
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "2 duplicate faces"));
  CHECK(p.report.faces == intact.report.faces);
  CHECK(p.report.volume == Approx(intact.report.volume).epsilon(1e-12));
}

TEST_CASE("repair: two overlapping boxes become their union") {
  // A = [0,2]^3 (8), B = [1.25,3.25] x [0.6,1.6] x [0.3,1.3] (2),
  // A ∩ B = [1.25,2] x [0.6,1.6] x [0.3,1.3] (0.75): |A ∪ B| = 9.25.
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2), 0.5);
  const SurfaceMesh b =
      make_box(Eigen::Vector3d(1.25, 0.6, 0.3), Eigen::Vector3d(3.25, 1.6, 1.3), 0.5);
  const PreparedMesh p = inspect_triangle_soup(soup_of(concatenated(a, b)), "boxes");
  check_sound(p);
  CHECK(p.report.shells == 1);
  CHECK(p.report.volume == Approx(9.25).epsilon(1e-12));
  // Areas 24 + 10, less A's face inside B (1 x 1) and B's part inside A (four sides
  // 0.75 x 1 and the end 1 x 1).
  CHECK(p.report.area == Approx(24.0 + 10.0 - 1.0 - (4 * 0.75 + 1.0)).epsilon(1e-12));
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "1 group of overlapping bodies"));
  CHECK(has_repair(p.report, "united 2 overlapping bodies"));
  CHECK(p.report.bounding_box.max.isApprox(Eigen::Vector3d(3.25, 2, 2)));

  // The second box inside out: a cavity wall crossing the first box's skin, or an inverted
  // body? That cannot be told (the winding number is −1 in B \ A), so the surface is used as
  // given, the crossing region reported as a defect: the part of B's skin that crosses A's.
  const TriangleSoup inverted = soup_of(concatenated(a, with_flipped_orientation(b)));
  MeshPreparationOptions measure_defects;
  measure_defects.measure_defects = true;
  const PreparedMesh q = inspect_triangle_soup(inverted, "boxes", measure_defects);
  CHECK(q.report.usable());
  CHECK(has_problem(q.report, MeshProblem::Status::defect, "pairs of intersecting faces"));
  REQUIRE(q.report.defects.size() == 1);
  const DefectZone& zone = q.report.defects.front();
  CHECK_THAT(zone.why, Catch::Contains("inside out over a region of volume 1.25"));
  // The curves lie on A's face x = 2 and B's faces inside A; the irregular pieces are all of
  // B's skin and A's face x = 2 (w = −1 or 0 beside them): the zone is within A ∪ B's box.
  CHECK((zone.box.min.array() >= Eigen::Array3d(0, 0, 0) - 1e-12).all());
  CHECK((zone.box.max.array() <= Eigen::Array3d(3.25, 2, 2) + 1e-12).all());
  CHECK(zone.box.max.x() > 3.0);
  MeshPreparationOptions refuse_defects;
  refuse_defects.measure_defects = false;
  const PreparedMesh refused = inspect_triangle_soup(inverted, "boxes", refuse_defects);
  CHECK(!refused.report.usable());
  CHECK_THAT(refused.report.refusal_message(),
             Catch::Contains("shells of opposite orientation cross"));

  MeshPreparationOptions strict;
  strict.repair_surface = false;
  const PreparedMesh r = inspect_triangle_soup(soup_of(concatenated(a, b)), "boxes", strict);
  CHECK(!r.report.usable());
  CHECK_THAT(r.report.refusal_message(), Catch::Contains("pairs of intersecting faces"));
}

TEST_CASE("repair: boxes crossing along edges they share after welding become their union") {
  // B's grid meets A's face x = 2 in A's own grid lines: welding makes the intersection curve
  // a loop of shared edges with four faces each, where the bodies pass through each other.
  // A = [0,2]^3, B = [1,3] x [0.5,1.5]^2: |A ∪ B| = 8 + 2 − 1 = 9.
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2), 0.5);
  const SurfaceMesh b =
      make_box(Eigen::Vector3d(1, 0.5, 0.5), Eigen::Vector3d(3, 1.5, 1.5), 0.5);
  const PreparedMesh p = inspect_triangle_soup(soup_of(concatenated(a, b)), "boxes");
  check_sound(p);
  CHECK(p.report.shells == 1);
  CHECK(p.report.volume == Approx(9.0).epsilon(1e-12));
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "8 non-manifold edges"));
  CHECK(has_repair(p.report, "united 2 overlapping bodies"));
}

TEST_CASE("repair: two cubes sharing an edge are split into two cubes touching along it") {
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.5);
  const SurfaceMesh b = make_box(Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(2, 2, 1), 0.5);
  const PreparedMesh p = inspect_triangle_soup(soup_of(concatenated(a, b)), "cubes");
  check_sound(p);
  CHECK(p.report.shells == 2);
  CHECK(p.report.volume == Approx(2.0).epsilon(1e-12));
  CHECK(p.report.faces == static_cast<std::size_t>(a.num_faces() + b.num_faces()));
  // The welded mesh has the edge x = y = 1 (two segments) with four faces each.
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "2 non-manifold edges"));
  CHECK(has_repair(p.report, "split 2 non-manifold edges (first at 1, 1, "));
  // Surface unchanged: the same triangles at the same places.
  CHECK(p.report.area == Approx(12.0).epsilon(1e-12));
}

TEST_CASE("repair: a vertex pushed slightly through the opposite wall is cut out and refilled") {
  // Plate 4 x 4 x 0.5, faces 0.25 across; the top vertex at (2, 2) is pushed to z = −0.05,
  // 0.05 through the bottom. Intact volume 8. The caller passes a repair length of 1 (h0).
  const SurfaceMesh plate = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 0.5), 0.25);
  Eigen::MatrixX3d v = plate.vertices();
  Eigen::Index moved = -1;
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (v.row(i).isApprox(Eigen::RowVector3d(2, 2, 0.5)))
      moved = i;
  REQUIRE(moved >= 0);
  v(moved, 2) = -0.05;
  const std::size_t pairs = find_self_intersections(v, plate.faces()).pairs;
  REQUIRE(pairs > 0);
  MeshPreparationOptions options;
  options.repair_length = 1.0;
  const PreparedMesh p = inspect_triangle_soup(soup_of(v, plate.faces()), "plate", options);
  check_sound(p);
  CHECK(has_problem(p.report, MeshProblem::Status::repaired,
                    std::to_string(pairs) + " pairs of intersecting faces within a shell"));
  CHECK(has_repair(p.report, "cut out "));
  // Both rims (around the pushed vertex on top, around the crossed faces below) are planar,
  // so the refilled plate is the intact one.
  CHECK(p.report.volume == Approx(8.0).epsilon(1e-9));
  CHECK(p.mesh.vertices().col(2).minCoeff() == 0.0);
  CHECK(p.mesh.vertices().col(2).maxCoeff() == 0.5);

  // With the default repair length (2 % of 5.68 = 0.11) the crossing region is too large to
  // cut out, and the fan below the bottom is inside out (w = −1): measured as given, the
  // region reported around the pushed vertex.
  MeshPreparationOptions measure_defects;
  measure_defects.measure_defects = true;
  const PreparedMesh q = inspect_triangle_soup(soup_of(v, plate.faces()), "plate", measure_defects);
  CHECK(q.report.usable());
  CHECK(has_problem(q.report, MeshProblem::Status::defect, "pairs of intersecting faces"));
  REQUIRE(q.report.defects.size() == 1);
  CHECK((q.report.defects.front().centre() - Eigen::Vector3d(2, 2, 0)).norm() < 0.3);
  CHECK(q.report.defects.front().size() < 1.0);
  CHECK_THAT(q.report.defects.front().why, Catch::Contains("inside out"));
  MeshPreparationOptions refuse_defects;
  refuse_defects.measure_defects = false;
  const PreparedMesh r = inspect_triangle_soup(soup_of(v, plate.faces()), "plate", refuse_defects);
  CHECK(!r.report.usable());
  CHECK_THAT(r.report.refusal_message(),
             Catch::Contains("pairs of intersecting faces") &&
                 Catch::Contains("larger than the repair length") &&
                 Catch::Contains("the repair length 0.114 (2 % of the bounding-box diagonal)"));
}

TEST_CASE("repair: a small fin on an edge is removed as a loose piece") {
  // A cube with a small triangle hanging off one of its edges (three faces at that edge).
  const SurfaceMesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.01);
  Eigen::MatrixX3d v(cube.num_vertices() + 1, 3);
  v.topRows(cube.num_vertices()) = cube.vertices();
  v.row(cube.num_vertices()) << 0.005, -0.01, -0.01;
  int a = -1, b = -1;
  for (Eigen::Index i = 0; i < cube.num_vertices(); ++i) {
    if (cube.vertices().row(i).isApprox(Eigen::RowVector3d(0, 0, 0)))
      a = static_cast<int>(i);
    if (cube.vertices().row(i).isApprox(Eigen::RowVector3d(0.01, 0, 0)))
      b = static_cast<int>(i);
  }
  REQUIRE(a >= 0);
  REQUIRE(b >= 0);
  Eigen::MatrixX3i f(cube.num_faces() + 1, 3);
  f.topRows(cube.num_faces()) = cube.faces();
  f.row(cube.num_faces()) << a, b, static_cast<int>(cube.num_vertices());
  const PreparedMesh p = inspect_triangle_soup(soup_of(v, f), "fin");
  check_sound(p);
  CHECK(p.report.faces == static_cast<std::size_t>(cube.num_faces()));
  CHECK(p.report.volume == Approx(1.0).epsilon(1e-12));
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "1 non-manifold edge"));
  CHECK(has_repair(p.report, "removed a loose open piece of 1 face"));
}

TEST_CASE("repair: a shell crossing itself over any size is replaced by the region it encloses") {
  // The bars of the damaged-mesh corpus that pass through themselves (the crossing 9 % and
  // 5 % of the diagonal, far above the repair length of 2 %): split along the crossing curves,
  // the boundary of the points of positive winding number kept, which is the union of the
  // bar's halves that CGAL's corefinement forms independently.
  for (const testing::DamagedMesh& d : testing::damaged_meshes()) {
    if (d.outcome != testing::DamageOutcome::resolved || !d.exact_intact)
      continue;
    CAPTURE(d.name);
    const PreparedMesh p = inspect_triangle_soup(soup_of(d.vertices, d.faces), d.name);
    check_sound(p);
    CHECK(p.report.shells == 1);
    CHECK(p.report.defects.empty());
    CHECK(has_problem(p.report, MeshProblem::Status::repaired,
                      "pairs of intersecting faces within a shell"));
    CHECK(has_repair(p.report, "split the surface along the curves where it crosses itself"));
    CHECK(p.report.volume == Approx(d.intact.signed_volume()).epsilon(1e-9));
    CHECK(p.report.area == Approx(d.intact.area()).epsilon(1e-9));
    // The region is reported where the bar crosses itself, with the volume before and after.
    bool located = false;
    for (const MeshProblem& q : p.report.problems)
      if (q.status == MeshProblem::Status::repaired &&
          q.consequence.find("as given (overlaps counted twice)") != std::string::npos)
        located = true;
    CHECK(located);
  }
}

TEST_CASE("repair: every mesh of the damaged corpus is usable, with its expected outcome") {
  // tests/support/damaged_meshes.hpp: crossing bars, bodies sharing faces, a folded strip,
  // patches of a plate, a spherical shell and a bracket pushed through the opposite wall
  // over 1–10 % of the diagonal, a block with a few dozen crossing pairs.
  for (const testing::DamagedMesh& d : testing::damaged_meshes()) {
    CAPTURE(d.name);
    MeshPreparationOptions options;
    options.measure_defects = true;
    const PreparedMesh p = inspect_triangle_soup(soup_of(d.vertices, d.faces), d.name, options);
    CAPTURE(p.report.refusal_message());
    REQUIRE(p.report.usable());
    const MeshValidation v = validate_mesh(p.mesh.vertices(), p.mesh.faces());
    CHECK(v.closed_manifold());
    CHECK(p.mesh.signed_volume() > 0.0);
    if (d.outcome == testing::DamageOutcome::measured_around) {
      // Measured as given: one region, where the damage is and about as large, named with
      // why; the surface still crosses itself there.
      REQUIRE(p.report.defects.size() == 1);
      const DefectZone& zone = p.report.defects.front();
      CHECK((zone.centre() - d.site).norm() < 0.5 * d.size);
      CHECK(zone.size() < 2.0 * d.size);
      CHECK(zone.size() > 0.1 * d.size);
      CHECK(zone.why.find("inside out") != std::string::npos);
      CHECK(has_problem(p.report, MeshProblem::Status::defect, "intersecting faces"));
      CHECK(find_self_intersections(p.mesh.vertices(), p.mesh.faces()).pairs > 0);
      // Refused, with the region, when defects are not to be measured.
      MeshPreparationOptions strict;
      strict.measure_defects = false;
      const PreparedMesh r = inspect_triangle_soup(soup_of(d.vertices, d.faces), d.name, strict);
      CHECK(!r.report.usable());
      CHECK(has_problem(r.report, MeshProblem::Status::refused, "intersecting faces"));
    } else {
      // A solid recovered: sound, nothing left crossing.
      check_sound(p);
      CHECK(p.report.defects.empty());
      if (d.outcome == testing::DamageOutcome::refilled) {
        CHECK(has_repair(p.report, "and refilled the hole"));
      } else if (d.outcome == testing::DamageOutcome::united) {
        CHECK(has_problem(p.report, MeshProblem::Status::repaired, "bodies sharing faces"));
        CHECK(p.report.volume == Approx(d.intact.signed_volume()).epsilon(1e-9));
        CHECK(p.report.area == Approx(d.intact.area()).epsilon(1e-9));
      } else {
        CHECK(has_repair(p.report, "split the surface along the curves where it crosses itself"));
      }
    }
  }
}
