// The wall thickness on the surface (analysis/wall_thickness.hpp, docs/theory.md section 5)
// on solids whose walls are known: a ball (the diameter, the curvature offset removed), a
// square plate (its thickness on every face, rims and corners included, where the sphere
// reading grows), a ring (both curved skins up to the end faces), a plate with a boss (the boss is the thick region and is located), and
// h0 from the part (2·V/A).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "analysis/wall_thickness.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

geometry::PreparedMesh prepared(const geometry::SurfaceMesh& mesh) {
  return analysis::prepare_triangles(mesh.vertices(), mesh.faces(), "test solid");
}

/// The plate [0, 12] × [0, 12] × [0, 2]: a 2 mm wall with rims on four sides.
constexpr double kPlateThickness = 2.0;
geometry::SurfaceMesh square_plate() {
  return geometry::make_box_solid(Eigen::Vector3d(0, 0, 0),
                                  Eigen::Vector3d(12, 12, kPlateThickness));
}

analysis::ThicknessOptions plate_options(analysis::ThicknessMeasure measure) {
  analysis::ThicknessOptions options;
  options.solve.h0 = kPlateThickness;
  options.solve.max_edge = 0.8;
  options.measure = measure;
  options.map_to_input = false;
  return options;
}

}  // namespace

TEST_CASE("wall thickness: a ball reads its diameter on every face, the offset a·h0 removed") {
  const double radius = 0.5, h0 = 0.3, a = 0.2;
  const geometry::SurfaceMesh ball = geometry::make_geodesic_sphere(
      radius, geometry::geodesic_frequency_for_edge(radius, 0.09));
  analysis::ThicknessOptions options;
  options.solve.h0 = h0;
  options.solve.a = a;
  options.map_to_input = false;
  const analysis::ThicknessResult result = analysis::measure_thickness(prepared(ball), options);
  REQUIRE(result.measure_column == "wall");
  const Eigen::ArrayXd error = (result.thickness.array() / (2.0 * radius) - 1.0).abs();
  CAPTURE(result.statistics.minimum, result.statistics.maximum, result.wall.filled_faces);
  CHECK(error.maxCoeff() < 0.02);
  // Every search found the centre: no face needed its neighbours.
  CHECK(result.wall.filled_faces == 0);
  CHECK((result.wall.depth.array() / radius - 1.0).abs().maxCoeff() < 0.02);
  // The sphere reading carries the diffusion offset: D + a·h0 (docs/theory.md section 3).
  options.measure = analysis::ThicknessMeasure::principal;
  const analysis::ThicknessResult sphere = analysis::measure_thickness(prepared(ball), options);
  CHECK(sphere.statistics.median > 2.0 * radius + 0.5 * a * h0);
}

TEST_CASE("wall thickness: a square plate reads its thickness up to its rims and corners") {
  const geometry::PreparedMesh plate = prepared(square_plate());
  const analysis::ThicknessResult wall =
      analysis::measure_thickness(plate, plate_options(analysis::ThicknessMeasure::wall));
  const Eigen::ArrayXd error = (wall.thickness.array() / kPlateThickness - 1.0).abs();
  CAPTURE(wall.statistics.minimum, wall.statistics.maximum, wall.wall.filled_faces);
  CHECK(error.maxCoeff() < 0.03);
  CHECK(std::abs(wall.statistics.median / kPlateThickness - 1.0) < 0.005);
  // The rim faces (normal in the plate's plane) searched along the plate and took their
  // neighbours' value; the broad faces found the mid-plane at half the thickness.
  const geometry::SurfaceMesh& mesh = wall.boundary.solver_mesh;
  Eigen::Index rim_faces = 0;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    if (std::abs(mesh.face_normals()(f, 2)) < 0.5) {
      ++rim_faces;
    } else if (wall.wall.rim_indicator(f) < 0.1) {
      CHECK(wall.wall.depth(f) == Approx(0.5 * kPlateThickness).epsilon(0.01));
    }
  }
  CHECK(wall.wall.filled_faces >= rim_faces);
  // Counted by reason: the rims as along the wall (their searches stopped as such), so that a
  // plain plate raises no warning (kFallbackWarningShare); every filled face counted once.
  double rim_area = 0.0;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    if (std::abs(mesh.face_normals()(f, 2)) < 0.5) rim_area += mesh.face_areas()(f);
  Eigen::Index counted = 0;
  double unexpected = 0.0;
  for (int k = 0; k < analysis::kFallbackKinds; ++k) {
    counted += wall.wall.fallback[std::size_t(k)].faces;
    if (analysis::Fallback(k) != analysis::Fallback::along_wall)
      unexpected += wall.wall.fallback[std::size_t(k)].area;
  }
  const analysis::FallbackFaces& along =
      wall.wall.fallback[std::size_t(analysis::Fallback::along_wall)];
  CAPTURE(rim_area, along.area, unexpected);
  CHECK(counted == wall.wall.filled_faces);
  CHECK(along.area >= 0.9 * rim_area);
  CHECK(unexpected < analysis::kFallbackWarningShare * mesh.face_areas().sum());
  CHECK(along.box.min.x() == Approx(0.0).margin(0.5));
  CHECK(along.box.max.x() == Approx(12.0).margin(0.5));

  // The sphere at the surface reads thinner within half a wall of a rim (no sphere of the
  // wall's diameter fits there). The exact edges follow it there, and a wall's width from
  // every rim read the sphere at the surface, within 3 % of the wall.
  const analysis::ThicknessResult sphere =
      analysis::measure_thickness(plate, plate_options(analysis::ThicknessMeasure::principal));
  CHECK(sphere.statistics.minimum < 0.9 * kPlateThickness);
  analysis::ThicknessOptions exact = plate_options(analysis::ThicknessMeasure::wall);
  exact.edges = analysis::EdgeMode::exact;
  const analysis::ThicknessResult edges = analysis::measure_thickness(plate, exact);
  CHECK(edges.statistics.minimum < 0.9 * kPlateThickness);
  CHECK(wall.statistics.minimum > 0.97 * kPlateThickness);
  double worst_inside = 0.0;
  Eigen::Index inside = 0;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d c = mesh.face_centroids().row(f).transpose();
    if ((c.head<2>().array() < kPlateThickness).any() ||
        (c.head<2>().array() > 12.0 - kPlateThickness).any())
      continue;
    ++inside;
    worst_inside = std::max(worst_inside, std::abs(edges.thickness(f) / kPlateThickness - 1.0));
  }
  CAPTURE(worst_inside, inside);
  CHECK(inside > 0);
  CHECK(worst_inside < 0.03);

  // A check at 1.1·t flags the whole plate as one region; at 0.9·t nothing.
  analysis::ThicknessOptions check = plate_options(analysis::ThicknessMeasure::wall);
  check.min_thickness = 1.1 * kPlateThickness;
  const analysis::ThicknessResult thin = analysis::measure_thickness(plate, check);
  REQUIRE(thin.regions.size() == 1);
  CHECK(thin.regions.front().area == Approx(plate.report.area).epsilon(1e-9));
  check.min_thickness = 0.9 * kPlateThickness;
  CHECK(analysis::measure_thickness(plate, check).regions.empty());
}

TEST_CASE("wall thickness: a search that runs along a wall stops within a few evaluations") {
  // The mid-surface search stops where it runs along a wall (analysis/wall_thickness.cpp,
  // MidSurfaceSearch): the field's wall lies across another direction than n (a plate's rims),
  // or the mid-surface would lie deeper than kAlongWallRatio walls (the end faces of a square
  // bar, where the field reads two equal across directions). Without either stop those
  // searches walk along the part to its far end; the readings stay the same (such faces take
  // their neighbours'), the cost does not.
  const analysis::ThicknessResult plate = analysis::measure_thickness(
      prepared(square_plate()), plate_options(analysis::ThicknessMeasure::wall));
  const double plate_per_face =
      double(plate.wall.evaluations) / double(plate.boundary.solver_mesh.num_faces());
  const geometry::SurfaceMesh bar =
      geometry::make_box_solid(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 16));
  const analysis::ThicknessResult rod = analysis::measure_thickness(
      prepared(bar), plate_options(analysis::ThicknessMeasure::wall));
  const double bar_per_face =
      double(rod.wall.evaluations) / double(rod.boundary.solver_mesh.num_faces());
  // Evaluations per face (deterministic for a mesh): the plate 1.66 with both stops, 2.24
  // without the first; the bar 2.34 with both, 2.55 without the second (its end faces are
  // 6 % of its area, and each of their searches otherwise walks on towards the far end).
  CAPTURE(plate_per_face, bar_per_face);
  CHECK(plate_per_face < 1.95);
  CHECK(bar_per_face < 2.45);
}

TEST_CASE("wall thickness: a ring reads its wall on both skins up to its end faces") {
  // Ring R1 = 4, R2 = 5.5 (wall 1.5), 3 high: curved skins with rims at both ends. There twice
  // the depth to the mid-surface is off by about ±t²H/2 (±7 % here), the skins' separation
  // at their shared mid-surface point is not (analysis/mid_surface_pairs.hpp).
  constexpr double kWall = 1.5;
  const int facets = 64;
  const geometry::SurfaceMesh ring = geometry::mesh_difference(
      geometry::make_faceted_cylinder(Eigen::Vector2d(0, 0), 5.5, 0.0, 3.0, facets),
      geometry::make_faceted_cylinder(Eigen::Vector2d(0, 0), 4.0, -1.0, 4.0, facets));
  analysis::ThicknessOptions options;
  options.solve.h0 = kWall;
  options.solve.max_edge = 0.45;
  options.map_to_input = false;
  const analysis::ThicknessResult result = analysis::measure_thickness(prepared(ring), options);
  const geometry::SurfaceMesh& mesh = result.boundary.solver_mesh;
  // The faceted skins are R·cos(π/64) from the axis at their flats' middles: the wall between
  // flats is 1.5·cos(π/64) to 1.5 (0.12 %).
  double worst = 0.0, worst_rim = 0.0;
  Eigen::Index paired = 0, rim_rows = 0;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    if (std::abs(mesh.face_normals()(f, 2)) > 0.5) continue;  // end faces: along the wall
    const double error = std::abs(result.thickness(f) / kWall - 1.0);
    worst = std::max(worst, error);
    const double z = mesh.face_centroids()(f, 2);
    if (std::min(z, 3.0 - z) < 0.5 * kWall) {
      ++rim_rows;
      worst_rim = std::max(worst_rim, error);
      paired += std::isfinite(result.wall.pair_thickness(f));
    }
  }
  const double per_face = double(result.wall.evaluations) / double(mesh.num_faces());
  CAPTURE(worst, worst_rim, paired, rim_rows, result.wall.paired_faces, per_face);
  // Evaluations per face (deterministic for a mesh): 1.95 with Newton's step forward until
  // the zero is bracketed; 2.50 where each such step went at least kDepthGrowth deeper (the
  // search then overshot the zero and came back by a third evaluation on most faces).
  CHECK(per_face < 2.1);
  CHECK(worst < 0.02);
  CHECK(worst_rim < 0.02);
  CHECK(paired > rim_rows / 2);  // most skin faces within half a wall of a rim were paired
}

TEST_CASE("wall thickness: the boss on a plate is the one thick region, located at the boss") {
  // A 2 mm plate 24 × 24 with a square boss 6 × 6, 4 mm high, on top (solid: thicker than
  // the plate everywhere).
  const geometry::SurfaceMesh plate =
      geometry::make_box_solid(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(24, 24, 2));
  const geometry::SurfaceMesh boss =
      geometry::make_box_solid(Eigen::Vector3d(9, 9, 1), Eigen::Vector3d(15, 15, 6));
  const geometry::PreparedMesh part = prepared(geometry::mesh_union(plate, boss));
  analysis::ThicknessOptions options;
  options.solve.h0 = 2.0;
  options.solve.max_edge = 1.0;
  options.max_thickness = 3.0;
  options.map_to_input = false;
  const analysis::ThicknessResult result = analysis::measure_thickness(part, options);
  CAPTURE(result.thick_regions.size(), result.statistics.median);
  REQUIRE(!result.thick_regions.empty());
  const analysis::ThickRegion& thickest = result.thick_regions.front();
  const auto in_boss = [](const Eigen::Vector3d& x) {
    return (x.head<2>().array() >= 9.0 - 1e-9).all() && (x.head<2>().array() <= 15.0 + 1e-9).all();
  };
  CHECK(in_boss(thickest.max_location));
  CHECK(thickest.maximum > 3.0);
  // The wall's middle under the thickest face lies inside the boss.
  REQUIRE(thickest.skeleton_point.allFinite());
  CHECK(in_boss(thickest.skeleton_point));
  // The plate away from the boss still reads its 2 mm.
  CHECK(std::abs(result.statistics.median / 2.0 - 1.0) < 0.01);
}

TEST_CASE("wall thickness: h0 from the part is 2·volume/area") {
  const geometry::PreparedMesh plate = prepared(square_plate());
  // V = 12·12·2 = 288, A = 2·144 + 4·24 = 384.
  CHECK(analysis::part_h0(plate.report) == Approx(2.0 * 288.0 / 384.0).epsilon(1e-12));
  analysis::ThicknessOptions options = plate_options(analysis::ThicknessMeasure::wall);
  options.h0_from_part = true;
  options.solve.h0 = 0.0;  // ignored
  const analysis::ThicknessResult result = analysis::measure_thickness(plate, options);
  CHECK(result.h0 == Approx(1.5).epsilon(1e-12));
  CHECK(result.h0_rule == "2*volume/area of the part");
  CHECK(std::abs(result.statistics.median / kPlateThickness - 1.0) < 0.01);
}
