// analysis/thickness_statistics.hpp: area-weighted quantiles, statistics and thin regions
// against values worked out by hand on a unit cube (12 triangles of area ½, two per side).
#include <catch2/catch.hpp>

#include "analysis/thickness_statistics.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

/// The unit cube [0, 1]³ as 12 right triangles, two per side.
geometry::SurfaceMesh unit_cube() {
  return geometry::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1.0);
}

/// 0.1 on the bottom side (z = 0), 0.2 on the top (z = 1), 1 elsewhere.
Eigen::VectorXd bottom_and_top_thin(const geometry::SurfaceMesh& cube) {
  Eigen::VectorXd thickness = Eigen::VectorXd::Ones(cube.num_faces());
  for (Eigen::Index f = 0; f < cube.num_faces(); ++f) {
    const double z = cube.face_centroids()(f, 2);
    if (z < 1e-12)
      thickness(f) = 0.1;
    else if (z > 1.0 - 1e-12)
      thickness(f) = 0.2;
  }
  return thickness;
}

}  // namespace

TEST_CASE("weighted quantile: interpolated between the area midpoints, clamped at both ends") {
  const Eigen::VectorXd values = (Eigen::VectorXd(4) << 3.0, 1.0, 4.0, 2.0).finished();
  const Eigen::VectorXd equal = Eigen::VectorXd::Ones(4);
  // Midpoints of equal areas at 1/8, 3/8, 5/8, 7/8 of the sorted values 1, 2, 3, 4.
  CHECK(analysis::weighted_quantile(values, equal, 0.5) == Approx(2.5));
  CHECK(analysis::weighted_quantile(values, equal, 0.25) == Approx(1.5));
  CHECK(analysis::weighted_quantile(values, equal, 0.05) == 1.0);
  CHECK(analysis::weighted_quantile(values, equal, 0.95) == 4.0);
  // Areas 3 and 1: midpoints at 3/8 and 7/8.
  const Eigen::VectorXd two = (Eigen::VectorXd(2) << 1.0, 2.0).finished();
  const Eigen::VectorXd areas = (Eigen::VectorXd(2) << 3.0, 1.0).finished();
  CHECK(analysis::weighted_quantile(two, areas, 0.5) == Approx(1.25));
}

TEST_CASE("thickness statistics: unmeasurable faces left out, their area counted") {
  const geometry::SurfaceMesh cube = unit_cube();
  REQUIRE(cube.num_faces() == 12);
  const analysis::ThicknessStatistics s =
      analysis::thickness_statistics(cube, bottom_and_top_thin(cube), 0.9);
  CHECK(s.measured_area == Approx(2.0));
  CHECK(s.unmeasurable_area == Approx(4.0));
  CHECK(s.minimum == 0.1);
  CHECK(s.maximum == 0.2);
  CHECK(s.mean == Approx(0.15));
  CHECK(s.median == Approx(0.15));  // between 0.1 at 3/8 and 0.2 at 5/8 of the area
  CHECK(s.min_location.z() == Approx(0.0).margin(1e-12));
  CHECK_THROWS_AS(analysis::thickness_statistics(cube, Eigen::VectorXd::Ones(12), 0.9), InputError);
}

TEST_CASE("thin regions: one per edge-connected set below the threshold, thinnest first") {
  const geometry::SurfaceMesh cube = unit_cube();
  const std::vector<analysis::ThinRegion> regions =
      analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.5);
  REQUIRE(regions.size() == 2);
  CHECK(regions[0].minimum == 0.1);
  CHECK(regions[1].minimum == 0.2);
  for (const analysis::ThinRegion& r : regions) {
    CHECK(r.faces == 2);
    CHECK(r.area == Approx(1.0));
    CHECK(r.centroid.x() == Approx(0.5));
    CHECK(r.centroid.y() == Approx(0.5));
  }
  CHECK(regions[0].centroid.z() == Approx(0.0).margin(1e-12));
  CHECK(regions[1].centroid.z() == Approx(1.0));
  CHECK(analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.1).empty());
  // Bottom and top are the two skins of one wall: faces across the wall from each other join
  // one region, its centroid between them.
  Eigen::VectorXi across = Eigen::VectorXi::Constant(cube.num_faces(), -1);
  std::vector<int> bottom, top;
  for (Eigen::Index f = 0; f < cube.num_faces(); ++f) {
    if (cube.face_normals()(f, 2) < -0.5) bottom.push_back(int(f));
    if (cube.face_normals()(f, 2) > 0.5) top.push_back(int(f));
  }
  REQUIRE(bottom.size() == 2);
  REQUIRE(top.size() == 2);
  across(bottom[0]) = top[0];
  const auto joined = analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.5, across);
  REQUIRE(joined.size() == 1);
  CHECK(joined[0].faces == 4);
  CHECK(joined[0].minimum == 0.1);
  CHECK(joined[0].centroid.z() == Approx(0.5));
  // Only selected faces join: at 0.15 the top (0.2) is not thin.
  CHECK(analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.15, across).size() == 1);
  CHECK(analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.15, across)[0].faces == 2);
  // Above every value: the whole closed surface is one region.
  const auto all = analysis::thin_regions(cube, bottom_and_top_thin(cube), 2.0);
  REQUIRE(all.size() == 1);
  CHECK(all[0].faces == 12);
  CHECK(all[0].area == Approx(6.0));
}

TEST_CASE("speck area: h0^2/4 or the request, never more than 0.1 % of the part's area") {
  // Part of area 6000: the cap is 6.
  CHECK(analysis::speck_area(std::nullopt, 2.0, 6000.0) == Approx(1.0));       // h0²/4
  CHECK(analysis::speck_area(std::nullopt, 10.0, 6000.0) == Approx(6.0));      // capped
  CHECK(analysis::speck_area(0.5, 10.0, 6000.0) == Approx(0.5));               // requested
  CHECK(analysis::speck_area(100.0, 1.0, 6000.0) == Approx(6.0));              // capped
  CHECK(analysis::speck_area(0.0, 1.0, 6000.0) == 0.0);
  // A part in metres with h0 = 5 (meant in mm): h0²/4 = 6.25 exceeds the part's area 0.024.
  CHECK(analysis::speck_area(std::nullopt, 5.0, 0.024) == Approx(2.4e-5));
}

TEST_CASE("thin check: every thin face counts, specks are set aside from the list only") {
  const geometry::SurfaceMesh cube = unit_cube();
  // Bottom (area 1, 0.1) and top (area 1, 0.2) thin below 0.5: two regions of area 1.
  std::vector<analysis::ThinRegion> regions =
      analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.5);
  REQUIRE(regions.size() == 2);

  SECTION("speck area below both regions: FAIL, both listed, no specks") {
    const analysis::ThinCheck check = analysis::thin_check(regions, 0.5);
    CHECK_FALSE(check.pass);
    CHECK(regions.size() == 2);
    CHECK(check.specks.empty());
    CHECK(check.thin_area == Approx(2.0));
    CHECK(check.speck_total == 0.0);
  }
  SECTION("speck area above each region but below their sum: FAIL, both set aside as specks") {
    const analysis::ThinCheck check = analysis::thin_check(regions, 1.5);
    CHECK_FALSE(check.pass);  // the old rule (no region left) passed here
    CHECK(regions.empty());
    REQUIRE(check.specks.size() == 2);
    CHECK(check.specks[0].minimum == Approx(0.1));  // most severe first
    CHECK(check.thin_area == Approx(2.0));
    CHECK(check.speck_total == Approx(2.0));
  }
  SECTION("speck area above the whole thin area: PASS, the specks reported") {
    const analysis::ThinCheck check = analysis::thin_check(regions, 2.5);
    CHECK(check.pass);
    CHECK(check.specks.size() == 2);
    CHECK(check.speck_total == Approx(2.0));
  }
  SECTION("speck area 0: any thin face fails") {
    const analysis::ThinCheck check = analysis::thin_check(regions, 0.0);
    CHECK_FALSE(check.pass);
    CHECK(regions.size() == 2);
  }
}

TEST_CASE("thin check: nothing thin passes with an empty list") {
  const geometry::SurfaceMesh cube = unit_cube();
  std::vector<analysis::ThinRegion> regions =
      analysis::thin_regions(cube, bottom_and_top_thin(cube), 0.05);
  const analysis::ThinCheck check = analysis::thin_check(regions, 0.0);
  CHECK(check.pass);
  CHECK(check.thin_area == 0.0);
  CHECK(check.specks.empty());
}
