// The thickness at the scale h0 (docs/theory.md, "The scale h0"): a detail much smaller than
// h0 does not make a wall thin, one at least h0 across does, and a noisy copy of a part reads
// its design walls, not its noise. measure_thickness with defaults (the wall reading, the
// graded solver mesh) on parts built by code:
//   * a 120 x 80 x 4 plate with a pit of diameter h0/4 and depth 0.3·t: not flagged at 0.9·t
//     with h0 = 0.9·t, flagged with h0 = the pit's diameter;
//   * the same plate with a groove 2·h0 wide and 0.3·t deep: flagged with h0 = 0.9·t, the
//     region on the groove;
//   * the plate with four holes and the L-bracket, seeded noise of σ = 3 % of the wall along
//     the normals of a fine export: the plate reads its wall as closely as its own wall at
//     scale h0 is to the design, the bracket's 1.5 mm rib is one thin region and nothing else
//     is flagged.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "analysis/thickness_statistics.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/mesh_preparation.hpp"
#include "tests/support/labelled_parts.hpp"
#include "tests/support/part_exports.hpp"

using namespace bemshape;
using Eigen::Vector3d;

namespace {

constexpr double kWall = 4.0;
/// The check's limit and the default h0 of `bemshape thickness --min-thickness 0.9·t`.
constexpr double kLimitRatio = 0.9;
constexpr double kDepth = 0.3 * kWall;
const Vector3d kPlateSize(120, 80, kWall);

analysis::ThicknessResult measure(const geometry::SurfaceMesh& mesh, double h0, double limit) {
  analysis::ThicknessOptions options;
  options.solve.h0 = h0;
  options.min_thickness = limit;
  options.map_to_input = false;
  return analysis::measure_thickness(
      analysis::prepare_triangles(mesh.vertices(), mesh.faces(), "part"), options);
}

/// The noisy copy of a labelled part's fine export (at least `min_faces`; every vertex moved
/// along its normal by a Gaussian of σ = `sigma_ratio`·t, seed 1, as the bench makes it),
/// measured with h0 = min-thickness = kLimitRatio·t.
struct NoisyRun {
  testing::LabelledPart part;
  analysis::ThicknessResult result;
};
NoisyRun measure_noisy_export(const std::string& name, long min_faces, double sigma_ratio) {
  NoisyRun run{testing::fine_export(name, min_faces), {}};
  const double t = run.part.nominal_wall;
  run.result = measure(testing::with_normal_noise(run.part.mesh, sigma_ratio * t, 1),
                       kLimitRatio * t, kLimitRatio * t);
  return run;
}

bool inside(const Vector3d& x, const Vector3d& lo, const Vector3d& hi) {
  return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
}

/// The labels of the solver faces of `result`, from the closest point of the clean part
/// (a noisy copy's faces carry the label of the design surface under them).
std::vector<testing::WallLabel> solver_labels(const testing::LabelledPart& part,
                                              const analysis::ThicknessResult& result) {
  const geometry::SurfaceMesh& mesh = result.boundary.solver_mesh;
  const geometry::ClosestPointQuery design(part.mesh);
  const geometry::ClosestPoints nearest = design.closest_points(mesh.face_centroids());
  std::vector<testing::WallLabel> labels(std::size_t(mesh.num_faces()));
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    labels[std::size_t(f)] =
        part.label(nearest.points.row(f).transpose(),
                   part.mesh.face_normals().row(nearest.faces(f)).transpose());
  return labels;
}

}  // namespace

TEST_CASE("thickness at scale h0: a pit of h0/4 is not a thin wall, it is at h0 = its diameter",
          "[thickness_scale]") {
  const double h0 = kLimitRatio * kWall;  // 3.6
  const double diameter = h0 / 4.0;       // 0.9
  const Eigen::Vector2d centre(60, 40);
  const geometry::SurfaceMesh plate = geometry::mesh_difference(
      geometry::make_box_solid(Vector3d::Zero(), kPlateSize),
      geometry::make_faceted_cylinder(centre, 0.5 * diameter, kWall - kDepth, kWall + 1.0, 16));
  const double limit = kLimitRatio * kWall;

  const analysis::ThicknessResult coarse = measure(plate, h0, limit);
  CAPTURE(coarse.statistics.minimum, coarse.regions.size());
  CHECK(coarse.regions.empty());
  CHECK(coarse.statistics.median == Approx(kWall).epsilon(0.01));

  const analysis::ThicknessResult fine = measure(plate, diameter, limit);
  CAPTURE(fine.statistics.minimum, fine.regions.size());
  REQUIRE(fine.regions.size() == 1);
  const analysis::ThinRegion& pit = fine.regions.front();
  CHECK(inside(pit.min_location, Vector3d(centre.x() - diameter, centre.y() - diameter, 0.0),
               Vector3d(centre.x() + diameter, centre.y() + diameter, kWall)));
  // The wall under the pit's floor is t − depth = 2.8.
  CHECK(pit.minimum == Approx(kWall - kDepth).epsilon(0.05));
}

TEST_CASE("thickness at scale h0: a groove 2·h0 wide is a thin wall at the default h0",
          "[thickness_scale]") {
  const double h0 = kLimitRatio * kWall;
  const double width = 2.0 * h0;
  const Vector3d lo(60 - 0.5 * width, -1.0, kWall - kDepth), hi(60 + 0.5 * width, 81.0, kWall + 1.0);
  const geometry::SurfaceMesh plate = geometry::mesh_difference(
      geometry::make_box_solid(Vector3d::Zero(), kPlateSize), geometry::make_box_solid(lo, hi));
  const analysis::ThicknessResult result = measure(plate, h0, kLimitRatio * kWall);
  CAPTURE(result.statistics.minimum, result.regions.size());
  REQUIRE(result.regions.size() == 1);
  const analysis::ThinRegion& groove = result.regions.front();
  CHECK(inside(groove.centroid, Vector3d(lo.x(), 0, 0), Vector3d(hi.x(), 80, kWall)));
  CHECK(groove.minimum == Approx(kWall - kDepth).epsilon(0.05));
  // The groove's floor reads its wall across the middle of the groove: at least half its
  // width is in the region.
  CHECK(groove.box_max.x() - groove.box_min.x() >= 0.5 * width);
}

TEST_CASE("thickness at scale h0: a noisy plate (sigma 3 % of t) reads its wall at scale h0",
          "[thickness_scale]") {
  // Every vertex of a 20,000-face export moved along its normal by σ = 3 % of t. The copy's
  // own wall at scale h0 — the mean height of each skin's vertices within a disc of diameter
  // h0, top minus bottom — is itself within 1 % of t on only about half of the plate (the
  // noise averaged over the ~20 vertices of each skin in a disc: σ·√2/√20 ≈ 1 % of t), so no
  // reading at that scale is within 1 % of t everywhere. The reading must be within 1 % of t
  // on at least as much area as that wall is, and meet the noisy parts' criteria of
  // docs/validation.md: median within 1 %, p05 within 3 %, at most 0.5 % of the area below
  // 0.9·t, no thin region.
  const testing::LabelledPart part = testing::fine_export("plate-holes", 20000);
  const double t = part.nominal_wall;
  const double h0 = kLimitRatio * t;
  const geometry::SurfaceMesh noisy = testing::with_normal_noise(part.mesh, 0.03 * t, 1);
  const analysis::ThicknessResult result = measure(noisy, h0, kLimitRatio * t);
  const std::vector<testing::WallLabel> labels = solver_labels(part, result);
  const geometry::SurfaceMesh& solver = result.boundary.solver_mesh;
  const Eigen::VectorXd& areas = solver.face_areas();
  double nominal = 0.0, within = 0.0, low = 0.0, own_nominal = 0.0, own_within = 0.0;
  std::vector<double> ratio, weight;
  for (Eigen::Index f = 0; f < areas.size(); ++f) {
    if (labels[std::size_t(f)].role != testing::WallRole::nominal) continue;
    nominal += areas(f);
    ratio.push_back(result.thickness(f) / t);
    weight.push_back(areas(f));
    if (std::abs(result.thickness(f) - t) <= 0.01 * t) within += areas(f);
    if (result.thickness(f) < kLimitRatio * t) low += areas(f);
    // The copy's own wall at scale h0 under the face's centroid (the export's vertices keep
    // their indices: a vertex's skin is that of its clean position).
    const Eigen::Vector2d c = solver.face_centroids().row(f).head<2>().transpose();
    double top = 0.0, bottom = 0.0;
    int n_top = 0, n_bottom = 0;
    for (Eigen::Index v = 0; v < noisy.num_vertices(); ++v) {
      if ((noisy.vertices().row(v).head<2>().transpose() - c).norm() > 0.5 * h0) continue;
      const double z = part.mesh.vertices()(v, 2);
      if (z == t) { top += noisy.vertices()(v, 2); ++n_top; }
      if (z == 0.0) { bottom += noisy.vertices()(v, 2); ++n_bottom; }
    }
    if (n_top == 0 || n_bottom == 0) continue;
    own_nominal += areas(f);
    if (std::abs(top / n_top - bottom / n_bottom - t) <= 0.01 * t) own_within += areas(f);
  }
  REQUIRE(nominal > 0.0);
  REQUIRE(own_nominal > 0.0);
  const Eigen::Map<const Eigen::VectorXd> r(ratio.data(), Eigen::Index(ratio.size()));
  const Eigen::Map<const Eigen::VectorXd> w(weight.data(), Eigen::Index(weight.size()));
  const double median = analysis::weighted_quantile(r, w, 0.5);
  const double p05 = analysis::weighted_quantile(r, w, 0.05);
  CAPTURE(median, p05, within / nominal, own_within / own_nominal, low / nominal);
  CHECK(within / nominal >= own_within / own_nominal);
  CHECK(std::abs(median - 1.0) <= 0.01);
  CHECK(p05 >= 0.97);
  CHECK(low / nominal <= 0.005);
  CHECK(result.regions.empty());
}

TEST_CASE("thickness at scale h0: the noisy bracket's 1.5 mm rib is one thin region, "
          "nothing else is",
          "[thickness_scale]") {
  const NoisyRun run = measure_noisy_export("l-bracket", 20000, 0.03);
  const testing::LabelledPart& part = run.part;
  const analysis::ThicknessResult& result = run.result;
  REQUIRE(part.features.size() == 1);
  const geometry::BoundingBox rib = part.features.front().box;
  CAPTURE(result.regions.size(), result.statistics.median);
  REQUIRE(result.regions.size() == 1);
  const analysis::ThinRegion& region = result.regions.front();
  CHECK(inside(region.centroid, rib.min, rib.max));
  // Its area is the rib's flagged faces: at least 90 % of the rib's surface.
  const std::vector<testing::WallLabel> labels = solver_labels(part, result);
  const Eigen::VectorXd& areas = result.boundary.solver_mesh.face_areas();
  double rib_area = 0.0;
  for (Eigen::Index f = 0; f < areas.size(); ++f)
    if (labels[std::size_t(f)].role == testing::WallRole::thin_feature) rib_area += areas(f);
  CHECK(region.area >= 0.9 * rib_area);
}

TEST_CASE("thickness at scale h0: the noisy taper's thin end is its one thin region, the "
          "wedges of its noisy convex edges are not walls",
          "[thickness_scale]") {
  // The bench's σ = 3 % copy of the 2–6 mm taper (at least 50,000 faces, seed 1). Some faces
  // on its noisy convex edges are tilted towards the neighbouring wall, and their searches
  // find a zero of s·n in the edge's wedge, a fraction of the wall deep, where twice the
  // depth and h_mid agree (0.29 at the 6 mm end, rim indicator 2.5): that agreement marks a
  // taper only below kRimFull (features/wall_thickness.hpp, kRimAgreement). Read as a wall,
  // it gave a false region at the thick end and spread into the thin end's region (minimum
  // 1.08 instead of 2.0).
  const NoisyRun run = measure_noisy_export("taper", 50000, 0.03);
  const double t = run.part.nominal_wall;
  const analysis::ThicknessResult& result = run.result;
  CAPTURE(result.regions.size(), result.statistics.median);
  REQUIRE(result.regions.size() == 1);
  const analysis::ThinRegion& region = result.regions.front();
  CAPTURE(region.minimum, region.centroid.transpose());
  // The taper is 2 mm thick at x = 0 and 6 at x = 60: below 0.9·4 from x = 0 to 24.
  CHECK(region.centroid.x() < 24.0);
  CHECK(region.minimum > 0.45 * t);
}

TEST_CASE("thickness at scale h0: the noisy plate_holes has one thin region, the thin rim of "
          "its rounded edge; noisy edge faces do not pair across the plate",
          "[thickness_scale]") {
  // plate_holes.STL refined to at least 50,000 faces, σ = 3 % of its 12.7 mm wall (seed 1),
  // as the bench runs it. A noisy face on the top edge, tilted towards the side wall, finds
  // a zero of s·n 0.8 deep in the edge's wedge (rim indicator 1.9, h_mid 2.9); taken as the
  // partner of faces on the rounded bottom edge across the plate, it read them 8–10 and a
  // second region (analysis/wall_thickness.cpp, kPartnerReadingRatio).
  const geometry::PreparedMesh prepared = geometry::prepare_mesh_file(
      std::string(BEMSHAPE_TEST_DATA_DIR) + "/meshes/plate_holes.STL");
  const double t = prepared.mesh.bounding_box().extent().minCoeff();
  const geometry::SurfaceMesh noisy = testing::with_normal_noise(
      testing::refined_to_faces(prepared.mesh, 50000), 0.03 * t, 1);
  const analysis::ThicknessResult result = measure(noisy, kLimitRatio * t, kLimitRatio * t);
  CAPTURE(result.regions.size(), result.statistics.median);
  std::ostringstream regions;
  for (const analysis::ThinRegion& region : result.regions)
    regions << "min " << region.minimum << ", area " << region.area << ", centroid ("
            << region.centroid.transpose() << "); ";
  INFO(regions.str());
  CHECK(result.regions.size() == 1);
}
