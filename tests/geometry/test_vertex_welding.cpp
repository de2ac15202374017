#include <catch2/catch.hpp>

#include "geometry/vertex_welding.hpp"

using namespace bemshape::geometry;

namespace {

/// Two triangles sharing the edge (1,0,0)–(0,1,0), stored as a soup of 6 corners; corner 4
/// is displaced by `offset` along x. Bounding-box diagonal √3.
void soup(double offset, Eigen::MatrixX3d& v, Eigen::MatrixX3i& f) {
  v.resize(7, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0,          //
      1 + offset, 0, 0, 1, 1, 1, 0, 1, 0,  //
      5, 5, 5;                             // used by no face
  // Row 4 is the apex (1,1,1); the shared corners are rows 1/3 and 2/5.
  f.resize(2, 3);
  f << 0, 1, 2, 3, 4, 5;
}

}  // namespace

TEST_CASE("exactly equal vertices merge, unreferenced ones are dropped") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  soup(0.0, v, f);
  const WeldResult w = weld_vertices(v, f);
  CHECK(w.merged_exact == 2);
  CHECK(w.merged_within_tolerance == 0);
  CHECK(w.unreferenced_removed == 1);
  CHECK(w.vertices.rows() == 4);
  CHECK(w.faces(1, 0) == w.faces(0, 1));
  CHECK(w.faces(1, 2) == w.faces(0, 2));
}

TEST_CASE("vertices closer than the relative tolerance merge, farther ones do not") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  const double diagonal = std::sqrt(3.0 * 25.0);  // bounding box [0,5]^3 (the unused vertex)
  const double tol = kWeldRelativeTolerance * diagonal;
  soup(0.5 * tol, v, f);
  WeldResult w = weld_vertices(v, f);
  CHECK(w.tolerance == Approx(tol));
  CHECK(w.merged_exact == 1);
  CHECK(w.merged_within_tolerance == 1);
  CHECK(w.faces(1, 0) == w.faces(0, 1));
  // The kept position is the first one met, not an average: merged vertices move ≤ tol.
  CHECK(w.vertices(w.faces(1, 0), 0) == 1.0);

  soup(3.0 * tol, v, f);
  w = weld_vertices(v, f);
  CHECK(w.merged_within_tolerance == 0);
  CHECK(w.faces(1, 0) != w.faces(0, 1));

  soup(0.5 * tol, v, f);
  w = weld_vertices(v, f, 0.0);  // tolerance stage off
  CHECK(w.merged_within_tolerance == 0);
}

TEST_CASE("minus zero and plus zero are the same coordinate") {
  Eigen::MatrixX3d v(6, 3);
  v << 0.0, 0, 0, 1, 0, 0, 0, 1, 0, -0.0, -0.0, 0, 0, 1, 0, 1, 1, 0;
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 3, 4, 5;
  CHECK(weld_vertices(v, f, 0.0).merged_exact == 2);
}
