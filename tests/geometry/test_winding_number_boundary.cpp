// The boundary of the region of positive winding number of a surface that crosses itself
// (geometry/winding_number_boundary.hpp), checked against its definition — at points
// sampled through the part, the result's winding number is 1 exactly where the input's is
// at least 1, and 0 elsewhere — and against CGAL's Boolean union of pieces that do not cross
// themselves (an independent construction of the same solid).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "geometry/constructive_solids.hpp"
#include "geometry/detail/cgal_autorefinement.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/self_intersection.hpp"
#include "geometry/winding_number.hpp"
#include "geometry/winding_number_boundary.hpp"
#include "tests/support/damaged_meshes.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

/// Points sampled on a grid through the bounding box of `v` (grown by a tenth), each
/// shifted by a fixed irrational fraction of a cell so that none lies on a face plane of
/// the axis-aligned test solids.
std::vector<Eigen::Vector3d> sample_points(const Eigen::MatrixX3d& v, int per_axis) {
  const Eigen::Vector3d lo = v.colwise().minCoeff().transpose(),
                        hi = v.colwise().maxCoeff().transpose();
  const Eigen::Vector3d margin = 0.1 * (hi - lo);
  const Eigen::Vector3d a = lo - margin, step = (hi - lo + 2 * margin) / per_axis;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < per_axis; ++i)
    for (int j = 0; j < per_axis; ++j)
      for (int k = 0; k < per_axis; ++k)
        points.push_back(a + step.cwiseProduct(Eigen::Vector3d(i + 0.5 * std::sqrt(2.0) - 0.2,
                                                               j + 0.5 * std::sqrt(3.0) - 0.3,
                                                               k + 0.5 * std::sqrt(5.0) - 0.6)));
  return points;
}

struct DefinitionCheck {
  int compared = 0;
  int wrong = 0;
};

/// At every sample point where the input's winding number is an integer to 1e-6 (points
/// away from the surface), the result's must be 1 if the input's is ≥ 1 and 0 otherwise.
DefinitionCheck check_definition(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                                 const WindingNumberBoundary& b, int per_axis) {
  DefinitionCheck c;
  for (const Eigen::Vector3d& x : sample_points(v, per_axis)) {
    const double w = winding_number(v, f, x);
    if (std::abs(w - std::round(w)) > 1e-6)
      continue;
    const double expected = std::round(w) >= 1.0 ? 1.0 : 0.0;
    const double got = winding_number(b.vertices, b.faces, x);
    ++c.compared;
    if (std::abs(got - expected) > 1e-6)
      ++c.wrong;
  }
  return c;
}

/// Closed, each edge of two faces or split into pairs by split_nonmanifold later: here every
/// edge has an even number of faces, and the result does not cross itself beyond the
/// rounding of the curves' points.
void check_closed(const WindingNumberBoundary& b) {
  const MeshValidation valid = validate_mesh(b.vertices, b.faces);
  CHECK(valid.boundary_edges.count == 0);
}

SurfaceMesh two_shells(const SurfaceMesh& a, const SurfaceMesh& b) {
  return concatenated(a, b);
}

}  // namespace

TEST_CASE("winding boundary: the exact predicates follow the right-hand rule") {
  const Eigen::Vector3d o(0, 0, 0), x(1, 0, 0), y(0, 1, 0);
  CHECK(detail::exact_orientation(o, x, y, Eigen::Vector3d(0.3, 0.3, 1e-300)) == 1);
  CHECK(detail::exact_orientation(o, x, y, Eigen::Vector3d(0.3, 0.3, -1)) == -1);
  CHECK(detail::exact_orientation(o, x, y, Eigen::Vector3d(5, -7, 0)) == 0);
  CHECK(detail::exact_coplanar_orientation(o, x, y, Eigen::Vector3d(4, 0.1, 0)) == 1);
  CHECK(detail::exact_coplanar_orientation(o, x, y, Eigen::Vector3d(4, -0.1, 0)) == -1);
  CHECK(detail::exact_coplanar_orientation(o, x, y, Eigen::Vector3d(4, 0, 0)) == 0);
}

TEST_CASE("winding boundary: a surface that does not cross itself is its own boundary") {
  const SurfaceMesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 0.5), 0.25);
  const WindingNumberBoundary b = winding_number_boundary(box.vertices(), box.faces());
  REQUIRE(b.ok);
  CHECK(b.faces.rows() == box.num_faces());
  CHECK(b.curve_edges == 0);
  CHECK(b.faces_split == 0);
  CHECK(b.volume == Approx(1.0).epsilon(1e-12));
  CHECK(b.signed_volume == Approx(1.0).epsilon(1e-12));
  CHECK(b.overlap_volume == 0.0);
  CHECK(b.negative_volume == 0.0);
  CHECK(b.min_winding == 0);
  CHECK(b.max_winding == 1);
  // A reversed surface encloses nothing under the positive rule.
  const SurfaceMesh flipped = with_flipped_orientation(box);
  const WindingNumberBoundary r = winding_number_boundary(flipped.vertices(), flipped.faces());
  REQUIRE(r.ok);
  CHECK(r.faces.rows() == 0);
  CHECK(r.negative_volume == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("winding boundary: two overlapping cubes become their union, the overlap counted") {
  // [0,1]³ and [0.5,1.5]³: union 2 − 1/8, overlap 1/8.
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.5);
  const SurfaceMesh b =
      make_box(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(1.5, 1.5, 1.5), 0.5);
  const SurfaceMesh both = two_shells(a, b);
  const WindingNumberBoundary u = winding_number_boundary(both.vertices(), both.faces());
  INFO(u.failure);
  REQUIRE(u.ok);
  CHECK(u.volume == Approx(1.875).epsilon(1e-12));
  CHECK(u.signed_volume == Approx(2.0).epsilon(1e-12));
  CHECK(u.overlap_volume == Approx(0.125).epsilon(1e-12));
  CHECK(u.negative_volume == 0.0);
  CHECK(u.max_winding == 2);
  CHECK(u.curve_edges > 0);
  check_closed(u);
  CHECK(find_self_intersections(u.vertices, u.faces).pairs == 0);
  const DefinitionCheck c = check_definition(both.vertices(), both.faces(), u, 12);
  CHECK(c.compared > 1000);
  CHECK(c.wrong == 0);
}

TEST_CASE("winding boundary: boxes whose faces lie on each other are united") {
  // [0,2]×[0,1]² and [1,3]×[0,1]²: four faces of each lie in the same planes, with grids that
  // agree or not; the refinement makes the pieces on each other equal (their steps add up).
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1), 0.5);
  for (const double edge : {0.5, 0.3}) {
    CAPTURE(edge);
    const SurfaceMesh b = make_box(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(3, 1, 1), edge);
    const SurfaceMesh both = two_shells(a, b);
    const WindingNumberBoundary u = winding_number_boundary(both.vertices(), both.faces());
    INFO(u.failure);
    REQUIRE(u.ok);
    // The perturbation moves vertices by at most 1e-9 of the diagonal (3.3).
    CHECK(u.volume == Approx(3.0).epsilon(1e-7));
    CHECK(u.overlap_volume == Approx(1.0).epsilon(1e-7));
    check_closed(u);
    const DefinitionCheck c = check_definition(both.vertices(), both.faces(), u, 10);
    CHECK(c.compared > 500);
    CHECK(c.wrong == 0);
  }
}

TEST_CASE("winding boundary: a box turned on the floor of another is united with it") {
  // B is A turned by 30° about the vertical through A's centre: their bottoms lie in one
  // plane, triangulated differently.
  const SurfaceMesh a = make_box(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 1), 0.5);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(std::numbers::pi / 6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const SurfaceMesh b = transformed(a, turn, Eigen::Vector3d::Zero());
  const SurfaceMesh both = two_shells(a, b);
  const WindingNumberBoundary u = winding_number_boundary(both.vertices(), both.faces());
  INFO(u.failure);
  REQUIRE(u.ok);
  CAPTURE(u.perturbed);
  // The union of two squares of side 2 turned by 30°: 8 − the octagon... compared with CGAL.
  const double reference = mesh_union(a, b).signed_volume();
  CHECK(u.volume == Approx(reference).epsilon(1e-7));
  check_closed(u);
  const DefinitionCheck c = check_definition(both.vertices(), both.faces(), u, 10);
  CHECK(c.compared > 500);
  CHECK(c.wrong == 0);
}

TEST_CASE(
    "winding boundary: a vertex pushed through the opposite wall leaves a region of "
    "negative winding number") {
  // Plate 4 x 4 x 0.5; the top vertex at (2, 2) pushed to z = −0.3: below the bottom, the
  // pushed fan encloses a pocket of w = −1 (the surface is inside out there).
  const SurfaceMesh plate = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 0.5), 0.5);
  Eigen::MatrixX3d v = plate.vertices();
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (v.row(i).isApprox(Eigen::RowVector3d(2, 2, 0.5)))
      v(i, 2) = -0.3;
  const WindingNumberBoundary b = winding_number_boundary(v, plate.faces());
  INFO(b.failure);
  REQUIRE(b.ok);
  CHECK(b.min_winding == -1);
  CHECK(b.negative_volume > 0.0);
  // ∫w = |Ω₊| − |{w ≤ −1}| when w ∈ {−1, 0, 1}.
  CHECK(b.signed_volume == Approx(b.volume - b.negative_volume).epsilon(1e-12));
  check_closed(b);
  const DefinitionCheck c = check_definition(v, plate.faces(), b, 12);
  CHECK(c.compared > 1000);
  CHECK(c.wrong == 0);
}

TEST_CASE("winding boundary: bars of the corpus crossing themselves are their union") {
  for (const testing::DamagedMesh& d : testing::damaged_meshes()) {
    if (d.outcome != testing::DamageOutcome::resolved || !d.exact_intact)
      continue;
    CAPTURE(d.name);
    const WindingNumberBoundary b = winding_number_boundary(d.vertices, d.faces);
    INFO(b.failure);
    REQUIRE(b.ok);
    CHECK(b.max_winding == 2);
    CHECK(b.min_winding == 0);
    CHECK(b.negative_volume == 0.0);
    CHECK(b.curves.diagonal().norm() < 2.0 * d.size);
    // The same solid as CGAL's union of the two halves that do not cross themselves.
    CHECK(b.volume == Approx(d.intact.signed_volume()).epsilon(1e-9));
    check_closed(b);
    const DefinitionCheck c = check_definition(d.vertices, d.faces, b, 16);
    CHECK(c.compared > 3000);
    CHECK(c.wrong == 0);
  }
}

TEST_CASE("winding boundary: welded bodies sharing faces of the corpus are their union") {
  const testing::DamagedMesh d = testing::damaged_mesh("overlapping_boxes");
  for (const bool refine : {false, true}) {
    CAPTURE(refine);
    const WindingNumberBoundary b = winding_number_boundary(d.vertices, d.faces, refine);
    INFO(b.failure);
    REQUIRE(b.ok);
    CHECK(b.volume == Approx(d.intact.signed_volume()).epsilon(1e-7));
    CHECK(b.negative_volume == 0.0);
    check_closed(b);
  }
}
