#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/surface_creases.hpp"
#include "tests/support/labelled_parts.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// A prism 100 long (x) and 30 deep (y) whose top is a roof of two planes meeting at the ridge
/// x = 50 with the dihedral angle `kink` [degrees].
SurfaceMesh roof(double kink) {
  const double rise = 50.0 * std::tan(0.5 * kink * kDegree);
  Polygon2 profile(5, 2);
  profile << 0, 0, 100, 0, 100, 10, 50, 10 + rise, 0, 10;
  const SurfaceMesh prism = extrude_polygon(profile, 0.0, 30.0);  // profile in (x, y), along z
  return prism;
}

long count(const std::vector<char>& flags) { return std::count(flags.begin(), flags.end(), 1); }

}  // namespace

TEST_CASE("creases of a box: its 12 edges, 8 corners and 6 patches") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(3, 2, 1), 0.5);
  const SurfaceCreases c = find_surface_creases(box);
  double length = 0.0;
  for (const DihedralEdge& e : c.creases) {
    CHECK(e.angle == Approx(std::numbers::pi / 2));
    length += (box.vertices().row(e.a) - box.vertices().row(e.b)).norm();
  }
  CHECK(length == Approx(4 * (3 + 2 + 1)));
  // The grid's vertices inside the box edges lie on straight creases; only the 8 box corners
  // are corners.
  CHECK(count(c.corner) == 8);
  CHECK(c.patches == 6);
  CHECK(c.crossed.empty());
  for (Eigen::Index v = 0; v < box.num_vertices(); ++v)
    CHECK(c.crease_degree(v) == (c.corner[static_cast<std::size_t>(v)] ? 3 : c.crease_degree(v)));
}

TEST_CASE("a lone shallow kink stays a crease, the facets of a cylinder are smoothed") {
  CreaseOptions options;
  options.smooth_angle_degrees = 15.0;
  options.chord_tolerance = 1.0;  // generous: only the facet rule decides
  options.min_chord = 0.1;
  SECTION("a 5° ridge between two large planes") {
    const SurfaceMesh prism = roof(5.0);
    const SurfaceCreases c = find_surface_creases(prism, options);
    CHECK(c.smoothed_edges() == 0);
    // Every edge of the prism with an angle is a crease, the ridge among them.
    const bool ridge = std::any_of(c.creases.begin(), c.creases.end(), [](const DihedralEdge& e) {
      return std::abs(e.angle - 5.0 * kDegree) < 1e-9 && !e.tessellated;
    });
    CHECK(ridge);
  }
  SECTION("a rod of 48 facets (7.5° each)") {
    const SurfaceMesh rod = make_faceted_cylinder(Eigen::Vector2d(0, 0), 10.0, 0.0, 40.0, 48);
    const SurfaceCreases c = find_surface_creases(rod, options);
    CHECK(c.smoothed_edges() == 48);  // every axial facet edge
    for (const DihedralEdge& e : c.creases)
      CHECK(e.angle == Approx(std::numbers::pi / 2));  // only the two rims are left
    CHECK(c.patches == 3);                             // mantle and two caps
    // The facets are 2·10·sin(π/48) wide.
    for (const CrossedEdge& e : c.crossed)
      if (e.smoothed)
        CHECK(e.facet_width == Approx(20.0 * std::sin(std::numbers::pi / 48)));
  }
  SECTION("the same rod with a chord tolerance too tight for the smallest chord") {
    options.chord_tolerance = 1e-4;
    const SurfaceMesh rod = make_faceted_cylinder(Eigen::Vector2d(0, 0), 10.0, 0.0, 40.0, 48);
    const SurfaceCreases c = find_surface_creases(rod, options);
    CHECK(c.smoothed_edges() == 0);
    const long tessellated = std::count_if(c.creases.begin(), c.creases.end(),
                                           [](const DihedralEdge& e) { return e.tessellated; });
    CHECK(tessellated == 48);
    CHECK(c.patches == 48 + 2);
  }
  SECTION("smoothing off (θ_s = 0): every candidate is a crease") {
    const SurfaceMesh rod = make_faceted_cylinder(Eigen::Vector2d(0, 0), 10.0, 0.0, 40.0, 48);
    const SurfaceCreases c = find_surface_creases(rod);
    CHECK(c.smoothed_edges() == 0);
    CHECK(c.patches == 48 + 2);
  }
}

TEST_CASE("normals filtered at a scale read a tube's radius, not its export's slivers") {
  // The labelled tube (radii 15 and 12, 128 facets of 2.8°) is a boolean's output: its caps
  // and facets are cut into slivers a few hundredths of a millimetre wide. Filtered at a scale,
  // neighbouring slivers of one facet get normals up to a degree apart; read against a
  // sliver's own height that would be a radius of a few hundredths, and the chord limits of
  // the size field would ask for elements as small.
  const SurfaceMesh tube = testing::make_labelled_part("tube", 64).mesh;
  CreaseOptions options;
  options.crease_angle_degrees = 5.0;
  options.smooth_angle_degrees = 15.0;
  options.chord_tolerance = 0.03;
  options.normal_scale = 1.35;
  const SurfaceCreases c = find_surface_creases(tube, options);
  REQUIRE(!c.crossed.empty());
  double smallest_radius = std::numeric_limits<double>::infinity();
  for (const CrossedEdge& e : c.crossed)
    smallest_radius = std::min(smallest_radius, e.facet_width / e.angle);
  // No edge reads a radius below half the inner wall's.
  CHECK(smallest_radius >= 6.0);
}

TEST_CASE("a rod's rims are curved creases: free to slide, their radius read over a window") {
  // A rod of radius 10 and 48 facets: its rims turn by 7.5° at each of their 48 vertices.
  const SurfaceMesh rod = make_faceted_cylinder(Eigen::Vector2d(0, 0), 10.0, 0.0, 40.0, 48);
  CreaseOptions options;
  options.smooth_angle_degrees = 15.0;  // the facet edges smoothed: two creases per rim vertex
  options.chord_tolerance = 1.0;
  SECTION("off by default: every turn is a corner") {
    const SurfaceCreases c = find_surface_creases(rod, options);
    CHECK(std::count(c.curved.begin(), c.curved.end(), 1) == 0);
  }
  SECTION("a turn of at most 10°") {
    options.curve_turn_degrees = 10.0;
    const SurfaceCreases c = find_surface_creases(rod, options);
    CHECK(std::count(c.curved.begin(), c.curved.end(), 1) == 2 * 48);
    int rim_vertices = 0;
    for (const CrossedEdge& e : c.crossed)
      if (e.a == e.b) {
        ++rim_vertices;
        CHECK(e.angle == Approx(7.5 * kDegree).epsilon(1e-9));
        // ρ = w/θ: the polygon's arc over its turn, 10·sin(π/48)/(π/48) = 9.993.
        CHECK(e.facet_width / e.angle == Approx(10.0).epsilon(2e-3));
      }
    CHECK(rim_vertices == 2 * 48);
  }
  SECTION("a turn of at most 5°: the 7.5° rims stay corners") {
    options.curve_turn_degrees = 5.0;
    const SurfaceCreases c = find_surface_creases(rod, options);
    CHECK(std::count(c.curved.begin(), c.curved.end(), 1) == 0);
  }
}

TEST_CASE("longest chord within the tolerance: sag⁻¹ in both regimes, continuous") {
  const double theta = 3.0 * kDegree, w = 0.5;
  // One facet edge crossed: sag = h·θ/4.
  const double small = 0.1 * w * theta;
  CHECK(longest_chord_within(theta, w, small) == Approx(4.0 * small / theta));
  // Many crossed: the arc sagitta h²/(8ρ) with ρ = w/θ.
  const double large = 10.0 * w * theta;
  const double h = longest_chord_within(theta, w, large);
  CHECK(h * h / (8.0 * w / theta) == Approx(large));
  // At δ = wθ/2 both give h = 2w.
  CHECK(longest_chord_within(theta, w, 0.5 * w * theta) == Approx(2.0 * w));
  CHECK(longest_chord_within(theta, w, 0.5 * w * theta * (1 + 1e-12)) == Approx(2.0 * w));
  CHECK(std::isinf(longest_chord_within(0.0, w, 1.0)));
}

TEST_CASE("crease detection refuses an open surface") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1.0);
  const SurfaceMesh open(box.vertices(), box.faces().topRows(box.num_faces() - 1));
  CHECK_THROWS_AS(find_surface_creases(open), InputError);
}
