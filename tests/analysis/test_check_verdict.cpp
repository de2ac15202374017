// The check's verdict as a property (docs/usage.md, "The check"): over the labelled parts,
// their copies scaled by 1e-3 and 25.4 (h0, the element size and the limits scaled alike) and
// the options that change regions (--min-region-area, --h0, --edges), no verdict is a PASS
// while the faces reading below the limit cover the speck area or more, and the speck area is
// never more than kSpeckPartFraction of the part's area. Each solve runs measure_thickness
// with a limit and a speck area of its own (the verdict as the front ends get it); the other
// limits and speck areas are then varied on its readings through the functions
// measure_thickness calls (thin_regions, speck_area, thin_check). The thin area is summed here
// from the readings, face by face, not taken from the regions.
#include <catch2/catch.hpp>

#include <optional>
#include <string>
#include <vector>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "analysis/thickness_statistics.hpp"
#include "geometry/constructive_solids.hpp"
#include "tests/support/labelled_parts.hpp"

using namespace bemshape;

namespace {

/// Facets per circle: coarse copies of the labelled parts keep the solves short; the verdict's
/// invariant does not depend on how finely the part is cut.
constexpr int kCoarseCircle = 8;
/// Solver element edge in nominal walls: a small uniform mesh (some 500-900 faces) instead of
/// the graded default (5,000 and more), for the same reason.
constexpr double kCoarseEdge = 2.5;

/// Area of the faces of `result` reading below `limit`.
double area_below(const analysis::ThicknessResult& result, double limit) {
  const Eigen::VectorXd& areas = result.boundary.solver_mesh.face_areas();
  double area = 0.0;
  for (Eigen::Index f = 0; f < result.thickness.size(); ++f)
    if (result.thickness(f) < limit)
      area += areas(f);
  return area;
}

struct Tally {
  int passes = 0;
  int fails = 0;
};

/// The invariants of one verdict on `below`, the area reading below the check's limit.
void check_one(const analysis::ThinCheck& check, const std::vector<analysis::ThinRegion>& regions,
               double below, double part_area, Tally& tally) {
  CHECK(check.speck_area <= analysis::kSpeckPartFraction * part_area * (1.0 + 1e-12));
  CHECK(check.thin_area == Approx(below).margin(1e-12 * part_area));
  if (check.pass) {
    ++tally.passes;
    CHECK((below == 0.0 || below < check.speck_area));
    CHECK(regions.empty());
  } else {
    ++tally.fails;
    CHECK((below >= check.speck_area && below > 0.0));
  }
  // Every thin face is in a listed region or a speck.
  double listed = check.speck_total;
  for (const analysis::ThinRegion& r : regions) {
    CHECK(r.area >= check.speck_area);
    listed += r.area;
  }
  for (const analysis::ThinRegion& r : check.specks)
    CHECK(r.area < check.speck_area);
  CHECK(listed == Approx(below).margin(1e-12 * part_area));
}

/// The speck areas asked for (--min-region-area): the default, none, one below and one far
/// above the cap, in square nominal walls.
std::vector<std::optional<double>> requested_speck_areas(double wall) {
  const double w2 = wall * wall;
  return {std::nullopt, 0.0, 0.5 * w2, 1e9 * w2};
}

/// Solves `mesh` (nominal wall `wall`) at h0 = h0_walls·wall with a check at 1.1·wall and the
/// speck area `request`, then checks that verdict and every other limit and speck area.
void check_part(const geometry::SurfaceMesh& mesh, double wall, double h0_walls,
                analysis::EdgeMode edges, std::size_t request, Tally& tally) {
  const std::vector<std::optional<double>> requested = requested_speck_areas(wall);
  analysis::ThicknessOptions options;
  options.solve.h0 = h0_walls * wall;
  options.solve.max_edge = kCoarseEdge * wall;
  options.edges = edges;
  options.min_thickness = 1.1 * wall;
  options.min_region_area = requested[request % requested.size()];
  options.map_to_input = false;
  const analysis::ThicknessResult result = analysis::measure_thickness(
      analysis::prepare_triangles(mesh.vertices(), mesh.faces(), "part"), options);
  const geometry::SurfaceMesh& solver_mesh = result.boundary.solver_mesh;
  const double part_area = solver_mesh.area();
  {
    INFO("measure_thickness's own check, min_region_area "
         << (options.min_region_area ? *options.min_region_area : -1.0));
    check_one(result.check, result.regions, area_below(result, *options.min_thickness),
              part_area, tally);
  }
  for (const double ratio : {0.3, 0.9, 1.1, 1.5, 3.0}) {
    const double limit = ratio * wall;
    const double below = area_below(result, limit);
    for (const std::optional<double>& area : requested) {
      INFO("limit " << limit << ", min_region_area " << (area ? *area : -1.0));
      std::vector<analysis::ThinRegion> regions =
          analysis::thin_regions(solver_mesh, result.thickness, limit, result.wall.partner);
      const double speck = analysis::speck_area(area, result.h0, part_area);
      const analysis::ThinCheck check = analysis::thin_check(regions, speck);
      check_one(check, regions, below, part_area, tally);
    }
  }
}

}  // namespace

TEST_CASE("check verdict: no PASS while the thin area reaches the speck area, at any scale",
          "[check]") {
  Tally tally;
  std::size_t request = 0;
  for (const std::string name : {"l-bracket", "plate-holes"}) {
    const testing::LabelledPart part = testing::make_labelled_part(name, kCoarseCircle);
    const double t = part.nominal_wall;
    for (const double scale : {1.0, 1e-3, 25.4}) {
      INFO(name << " scale " << scale);
      const geometry::SurfaceMesh mesh =
          geometry::transformed(part.mesh, Eigen::Affine3d(Eigen::Scaling(scale)));
      check_part(mesh, t * scale, 1.0, analysis::EdgeMode::wall, request++, tally);
    }
    // --h0 changes the readings and the default speck area h0²/4; --edges exact the readings
    // at convex edges (down to 0 at sharp ones).
    INFO(name << " h0 " << 2 * t);
    check_part(part.mesh, t, 2.0, analysis::EdgeMode::wall, request++, tally);
    INFO(name << " edges exact");
    check_part(part.mesh, t, 1.0, analysis::EdgeMode::exact, request++, tally);
  }
  // Both verdicts occur: the property is not met by a check that always fails.
  CHECK(tally.passes > 0);
  CHECK(tally.fails > 0);
}
