#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/graded_remeshing.hpp"
#include "geometry/isotropic_remeshing.hpp"
#include "tests/support/labelled_parts.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/surface_distance.hpp"

using namespace bemshape;
using namespace bemshape::geometry;
using namespace bemshape::testing;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

/// The smallest angle the remesher reaches on every test part [degrees]: the operations keep
/// kMinAngleBoundDegrees (20°); the last splits of the uniform mode may halve an angle of a
/// good triangle, to no less than this.
constexpr double kAngleReached = 19.5;

/// Solver-mesh default edge of h0: 1.5·a·h0 with a = 0.2.
double fine_edge(double h0) { return 0.3 * h0; }

/// A labelled part as its STL export would be read: welded, validated, repaired.
PreparedMesh prepared_part(const std::string& name, double* h0 = nullptr) {
  const LabelledPart part = make_labelled_part(name);
  TriangleSoup soup;
  soup.vertices = part.mesh.vertices();
  soup.faces = part.mesh.faces();
  PreparedMesh prepared = inspect_triangle_soup(soup, name);
  REQUIRE(prepared.report.usable());
  if (h0)
    *h0 = 0.9 * part.nominal_wall;
  return prepared;
}

/// Length of each input crease covered by output edges lying on it: an output edge whose two
/// ends are within `tolerance` of the crease's line contributes the overlap of its projection
/// with the crease segment (the remesher may drop a vertex inside a straight crease, so one
/// output edge can span several input crease edges). Each output edge counted once.
std::vector<double> crease_coverage(const SurfaceMesh& input, const SurfaceCreases& creases,
                                    const SurfaceMesh& output, double tolerance) {
  std::vector<double> covered(creases.creases.size(), 0.0);
  const Eigen::MatrixX3d& V = output.vertices();
  for (Eigen::Index f = 0; f < output.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = output.faces()(f, k), b = output.faces()(f, (k + 1) % 3);
      if (a > b)
        continue;  // the edge is seen from both faces; count it from one
      const Eigen::Vector3d p = V.row(a), q = V.row(b);
      for (std::size_t c = 0; c < creases.creases.size(); ++c) {
        const Eigen::Vector3d s = input.vertices().row(creases.creases[c].a);
        const Eigen::Vector3d t = input.vertices().row(creases.creases[c].b);
        if ((s.cwiseMin(t) - p.cwiseMax(q)).maxCoeff() > tolerance ||
            (p.cwiseMin(q) - s.cwiseMax(t)).maxCoeff() > tolerance)
          continue;  // the boxes do not meet
        const Eigen::Vector3d u = (t - s).normalized();
        const double sp = (p - s).dot(u), sq = (q - s).dot(u);
        if ((p - s - sp * u).norm() > tolerance || (q - s - sq * u).norm() > tolerance)
          continue;  // not on the crease's line
        const double overlap =
            std::min(std::max(sp, sq), (t - s).norm()) - std::max(std::min(sp, sq), 0.0);
        if (overlap > 0.0)
          covered[c] += overlap;
      }
    }
  return covered;
}

/// Every promise of graded_remeshing.hpp for a remeshing of `input` that keeps its creases.
void require_same_surface(const SurfaceMesh& input, const SurfaceMesh& output,
                          const SurfaceCreases& creases) {
  const MeshValidation v = validate_mesh(output.vertices(), output.faces());
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
  CHECK(!v.zero_area_faces);
  CHECK(!v.collapsed_faces);
  CHECK(!v.needle_faces);
  CHECK(v.shells == validate_mesh(input.vertices(), input.faces()).shells);
  CHECK(output.signed_volume() > 0.0);
  CHECK(output.smallest_angle_degrees() >= kAngleReached);
  const double diagonal = input.bounding_box().diagonal();
  CHECK(testing::max_distance_to_surface(output.vertices(), input.vertices(), input.faces()) <=
        1e-9 * diagonal);
  // The input's vertices are on the output too: the two surfaces coincide.
  CHECK(testing::max_distance_to_surface(input.vertices(), output.vertices(), output.faces()) <=
        1e-9 * diagonal);
  // Two surfaces within d of each other enclose volumes that differ by at most about d·area.
  CHECK(std::abs(output.signed_volume() - input.signed_volume()) <= 1e-9 * diagonal * input.area());
  CHECK(output.area() == Approx(input.area()).epsilon(1e-9));
  // Each crease of the input is a union of output edges.
  const std::vector<double> covered = crease_coverage(input, creases, output, 1e-9 * diagonal);
  for (std::size_t c = 0; c < creases.creases.size(); ++c) {
    const double length =
        (input.vertices().row(creases.creases[c].a) - input.vertices().row(creases.creases[c].b))
            .norm();
    CHECK(covered[c] == Approx(length).epsilon(1e-9));
  }
}

/// A remeshed surface whose chords may cross the input's facets: angles above the bound
/// reached, closed, manifold and consistently oriented, every vertex on the input surface,
/// and the volume within `delta` (the chord tolerance) times the area of the input's.
void check_within_chords(const SurfaceMesh& output, const SurfaceMesh& input, double delta) {
  CHECK(output.smallest_angle_degrees() >= kAngleReached);
  const MeshValidation v = validate_mesh(output.vertices(), output.faces());
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
  const double diagonal = input.bounding_box().diagonal();
  CHECK(testing::max_distance_to_surface(output.vertices(), input.vertices(), input.faces()) <=
        1e-9 * diagonal);
  CHECK(std::abs(output.signed_volume() - input.signed_volume()) <= delta * input.area());
}

GradedMeshParameters parameters_for(double h0) {
  GradedMeshParameters p;
  p.h0 = h0;
  p.fine_edge = fine_edge(h0);
  p.smooth_angle_degrees = 0.0;  // every crease kept: the output surface is the input's
  return p;
}

}  // namespace

TEST_CASE("graded remeshing of the plate with holes: the input surface, far fewer faces") {
  double h0 = 0.0;
  const PreparedMesh plate = prepared_part("plate-holes", &h0);
  const GradedMesh graded = graded_solver_mesh(plate.mesh, parameters_for(h0));
  require_same_surface(plate.mesh, graded.mesh, find_surface_creases(plate.mesh));
  // The uniform default mesh has about area/(√3/4·h_f²) faces.
  const double uniform = plate.mesh.area() / (std::sqrt(3.0) / 4.0 * std::pow(fine_edge(h0), 2));
  CHECK(static_cast<double>(graded.mesh.num_faces()) < 0.4 * uniform);
  // h_f at the creases, several h0 on the broad faces.
  CHECK(graded.report.min_edge < fine_edge(h0));
  CHECK(graded.report.max_edge > h0);
  CHECK(graded.report.min_angle_degrees >= kAngleReached);
  CHECK(graded.report.area_by_reason[static_cast<std::size_t>(SizeReason::crease)] > 0.0);
  CHECK(graded.report.area_by_reason[static_cast<std::size_t>(SizeReason::wall_thickness)] > 0.0);
}

TEST_CASE("graded remeshing of every labelled part keeps its surface and angles") {
  for (const std::string& name : labelled_part_names()) {
    if (name == "large-tray")
      continue;  // 356 mm, for the benchmarks: the brute-force distances here are O(V·F)
    INFO(name);
    double h0 = 0.0;
    const PreparedMesh part = prepared_part(name, &h0);
    const GradedMesh graded = graded_solver_mesh(part.mesh, parameters_for(h0));
    require_same_surface(part.mesh, graded.mesh, find_surface_creases(part.mesh));
  }
}

TEST_CASE("uniform and graded remeshing over a range of sizes on the bundled meshes") {
  // Each mesh with an h0 of its scale; sizes from 0.2·h0 up to 20 times the default edge.
  struct Case {
    std::string file;
    double h0;
    std::vector<double> edges;  // multiples of h0
  };
  const std::vector<Case> cases = {
      {"unit_sphere.STL", 0.5, {0.2, 0.6, 2.0, 6.0}},
      {"cylinder.stl", 0.5, {0.2, 0.6, 2.0, 6.0}},
      {"plate_holes.STL", 11.4, {0.3, 1.2, 6.0}},
  };
  for (const Case& c : cases) {
    const PreparedMesh input = prepare_mesh_file(data + "/meshes/" + c.file);
    const SurfaceCreases creases = find_surface_creases(input.mesh);
    for (const double ratio : c.edges) {
      INFO(c.file << " uniform edge " << ratio << "·h0");
      RemeshingOptions options;
      const SurfaceMesh uniform = refine_uniformly(input.mesh, ratio * c.h0, options).mesh;
      require_same_surface(input.mesh, uniform, creases);
      CHECK(uniform.max_edge_length() <= options.max_edge_ratio * ratio * c.h0 * (1 + 1e-12));
    }
    for (const double h0 : {c.h0, 4.0 * c.h0}) {
      INFO(c.file << " graded, h0 " << h0);
      require_same_surface(input.mesh, graded_solver_mesh(input.mesh, parameters_for(h0)).mesh,
                           creases);
    }
  }
}

TEST_CASE("a coarse uniform mesh of a plate has no degenerate triangle") {
  // CGAL's isotropic remeshing made (29,0,0), (28,0,0), (27,0,0) from this plate at edge 8.
  const SurfaceMesh plate = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(120, 80, 4), 1.0);
  for (const double edge : {8.0, 20.0, 60.0}) {
    INFO("edge " << edge);
    const SurfaceMesh coarse = refine_uniformly(plate, edge).mesh;
    require_same_surface(plate, coarse, find_surface_creases(plate));
    CHECK(coarse.max_edge_length() <= 1.3 * edge);
    // The --max-edge mesher (CGAL, or this where CGAL degenerates): no degenerate triangle.
    const SurfaceMesh cgal = refine_to_edge_length(plate, edge);
    const MeshValidation v = validate_mesh(cgal.vertices(), cgal.faces());
    CHECK(v.closed_manifold());
    CHECK(!v.zero_area_faces);
    CHECK(!v.collapsed_faces);
    CHECK(cgal.smallest_angle_degrees() > 1e-3);
    CHECK(cgal.signed_volume() == Approx(plate.signed_volume()).epsilon(1e-9));
  }
}

TEST_CASE("a tessellated tube: smoothed facets give far fewer faces within the chord tolerance") {
  double h0 = 0.0;
  const PreparedMesh tube = prepared_part("tube", &h0);
  GradedMeshParameters p = parameters_for(h0);
  const GradedMesh kept = graded_solver_mesh(tube.mesh, p);
  p.smooth_angle_degrees = 15.0;
  p.chord_tolerance_ratio = 5e-3;
  const GradedMesh smoothed = graded_solver_mesh(tube.mesh, p);
  CHECK(smoothed.report.smoothed_edges > 0);
  CHECK(smoothed.mesh.num_faces() < kept.mesh.num_faces() / 2);
  check_within_chords(smoothed.mesh, tube.mesh, p.chord_tolerance_ratio * h0);
}

TEST_CASE("a tube's round rims: curved crease vertices let the rims take the field's sizes") {
  // The labelled tube's rims are polygons of 128 creases turning by 2.8° at each vertex; as
  // corners they would keep every vertex of the export and the faces around them tiny.
  double h0 = 0.0;
  const PreparedMesh tube = prepared_part("tube", &h0);
  // The wall reading's mesh (analysis::wall_reading_mesh_parameters).
  GradedMeshParameters p = parameters_for(h0);
  p.max_edge_ratio = 2.0;
  p.wall_thickness_ratio = 1.0;
  p.refine_creases = false;
  p.min_size_ratio = 0.5;
  p.min_chord_ratio = 0.0;
  p.chord_thickness_ratio = 0.01;
  p.crease_angle_degrees = 5.0;
  p.smooth_angle_degrees = 15.0;
  p.normal_scale_ratio = 0.5;
  p.require_facet_strips = false;
  const GradedMesh corners = graded_solver_mesh(tube.mesh, p);
  p.curve_turn_degrees = 15.0;
  const GradedMesh curved = graded_solver_mesh(tube.mesh, p);
  CHECK(curved.mesh.num_faces() < corners.mesh.num_faces() * 3 / 4);
  // A rim vertex lies on the rim's polygon; the chord tolerance is c_δ times the 3 mm wall.
  check_within_chords(curved.mesh, tube.mesh, p.chord_thickness_ratio * 3.0);
}

TEST_CASE("graded remeshing refuses empty, open and runaway input") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1.0);
  const SurfaceMesh open(box.vertices(), box.faces().topRows(box.num_faces() - 1));
  CHECK_THROWS_AS(graded_solver_mesh(open, parameters_for(0.5)), InputError);
  CHECK_THROWS_AS(graded_solver_mesh(SurfaceMesh(), parameters_for(0.5)), InputError);
  GradedMeshParameters p = parameters_for(0.5);
  p.remeshing.max_faces = 100;
  CHECK_THROWS_AS(graded_solver_mesh(box, p), ResourceError);
}

TEST_CASE("graded solver mesh keeps an input that is already fine enough, remeshes a coarse one") {
  // A geodesic ball of radius 1 at edge 0.09 with h0 = 0.3: every edge within 4/3 of h_f, angles
  // near 60°, and no more than twice the faces the field asks for.
  const SurfaceMesh ball = make_geodesic_sphere(1.0, geodesic_frequency_for_edge(1.0, 0.09));
  GradedMeshParameters p;
  p.h0 = 0.3;
  p.fine_edge = fine_edge(p.h0);
  p.curvature_ratio = 0.05;  // elements of 0.05 rad of arc, never below h_f: h_f on this ball
  const GradedMesh kept = graded_solver_mesh(ball, p);
  CHECK(kept.report.kept_input);
  CHECK(kept.mesh.vertices() == ball.vertices());
  CHECK(kept.mesh.faces() == ball.faces());
  CHECK(kept.report.max_edge_ratio <= 4.0 / 3.0);
  CHECK(static_cast<double>(kept.report.faces) <= kKeepInputFaceRatio * kept.report.field_faces);
  // Off: the same ball is remeshed.
  p.keep_input_face_ratio = 0.0;
  CHECK(!graded_solver_mesh(ball, p).report.kept_input);
  // A coarse ball (edges far above h_f) is remeshed.
  const SurfaceMesh coarse = make_geodesic_sphere(1.0, 4);
  p.keep_input_face_ratio = kKeepInputFaceRatio;
  const GradedMesh refined = graded_solver_mesh(coarse, p);
  CHECK(!refined.report.kept_input);
  CHECK(refined.mesh.num_faces() > coarse.num_faces());
}
