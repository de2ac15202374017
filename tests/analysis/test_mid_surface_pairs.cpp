// The skins that share a mid-surface point (analysis/mid_surface_pairs.hpp): the partner is
// the opposite face whose mid-surface point is nearest, the reading is the skins' separation
// along the bisector of their normals, and faces without an opposite skin get none.
#include <catch2/catch.hpp>

#include <cmath>

#include "analysis/mid_surface_pairs.hpp"

using namespace bemshape;

namespace {

/// Four faces as a wall's skins would see them: 0 on top (z = 2, normal +z), 1 below it
/// (z = 0, normal −z) shifted by 0.1 in x, 2 far along the wall (x = 20) on the bottom skin,
/// and 3, an end face (normal +x) beside face 0.
geometry::SurfaceMesh four_skins() {
  Eigen::MatrixX3d v(12, 3);
  v << 0, 0, 2, 1, 0, 2, 0, 1, 2,       // face 0: counter-clockwise seen from +z
      0.1, 0, 0, 0.1, 1, 0, 1.1, 0, 0,  // face 1: clockwise seen from +z, normal −z
      20, 0, 0, 20, 1, 0, 21, 0, 0,     // face 2: normal −z, 20 along the wall
      2, 0, 0, 2, 1, 0, 2, 0, 1;        // face 3: normal +x
  Eigen::MatrixX3i f(4, 3);
  f << 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11;
  return geometry::SurfaceMesh(v, f);
}

}  // namespace

TEST_CASE("mid-surface pairs: the opposite skin at the same mid-surface point gives the wall") {
  const geometry::SurfaceMesh mesh = four_skins();
  REQUIRE(mesh.face_normals()(0, 2) == Approx(1.0));
  REQUIRE(mesh.face_normals()(1, 2) == Approx(-1.0));
  REQUIRE(mesh.face_normals()(3, 0) == Approx(1.0));
  // Depths as a search would find them on a 2-thick wall whose mid-surface is off the middle
  // (near a rim): 0.8 from the top and 1.3 from the bottom, so 2τ reads 1.6 and 2.6; the end
  // face's search ran along the wall.
  Eigen::VectorXd depth(4);
  depth << 0.8, 1.3, 1.0, 5.0;
  Eigen::MatrixX3d mid(4, 3);
  for (Eigen::Index f = 0; f < 4; ++f)
    mid.row(f) = mesh.face_centroids().row(f) - depth(f) * mesh.face_normals().row(f);
  const Eigen::Array<bool, Eigen::Dynamic, 1> all = Eigen::Array<bool, 4, 1>::Constant(true);
  const analysis::MidSurfacePairs pairs = analysis::mid_surface_pairs(mesh, mid, depth, all, all);
  const Eigen::VectorXd& t = pairs.thickness;
  CAPTURE(t.transpose());
  CHECK(t(0) == Approx(2.0).epsilon(1e-12));  // face 1 is its partner, not face 2
  CHECK(t(1) == Approx(2.0).epsilon(1e-12));
  CHECK(std::isnan(t(2)));  // no top face within reach of its mid-surface point
  CHECK(std::isnan(t(3)));  // no face opposite an end face
  CHECK(pairs.partner(0) == 1);
  CHECK(pairs.partner(1) == 0);
  CHECK(pairs.partner(2) == -1);
  CHECK(pairs.partner(3) == -1);

  // Only the faces asked for, and none without a mid-surface point.
  Eigen::Array<bool, Eigen::Dynamic, 1> first = all;
  first.tail(3).setConstant(false);
  depth(1) = std::nan("");
  mid.row(1).setConstant(std::nan(""));
  const analysis::MidSurfacePairs u = analysis::mid_surface_pairs(mesh, mid, depth, first, all);
  CHECK(u.thickness.array().isNaN().all());
  CHECK((u.partner.array() == -1).all());

  // Partners only among the faces whose search crossed their wall.
  depth(1) = 1.3;
  mid.row(1) = mesh.face_centroids().row(1) - depth(1) * mesh.face_normals().row(1);
  Eigen::Array<bool, Eigen::Dynamic, 1> crossed = all;
  crossed(1) = false;
  CHECK(analysis::mid_surface_pairs(mesh, mid, depth, all, crossed).partner(0) == -1);
}

namespace {

/// Two faces of a 2-thick wall: 0 on top (z = 2, normal +z) and 1 below it, its normal tilted
/// by `tilt` [rad] from −z about the y axis, both reaching the mid-surface point (0.3, 0.3, 1)
/// (depths `depth0` and `depth1`, whatever they are, so that only the rule under test decides),
/// face 1's moved by `offset` along x.
analysis::MidSurfacePairs two_skins(double tilt, double depth0, double depth1,
                                    double offset = 0.0) {
  const Eigen::Vector3d n1(-std::sin(tilt), 0.0, -std::cos(tilt));
  // Face 1: a small triangle through (0.3, 0.3, 0) with normal n1.
  const Eigen::Vector3d u = Eigen::Vector3d::UnitY(), w = u.cross(n1);  // w × u = n1
  const Eigen::Vector3d c1(1.0 / 3.0, 1.0 / 3.0, 0.0);
  Eigen::MatrixX3d v(6, 3);
  v.row(0) << 0, 0, 2;
  v.row(1) << 1, 0, 2;
  v.row(2) << 0, 1, 2;
  v.row(3) = (c1 - 0.4 * w - 0.4 * u).transpose();
  v.row(4) = (c1 + 0.8 * w - 0.4 * u).transpose();
  v.row(5) = (c1 - 0.4 * w + 0.8 * u).transpose();
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 3, 4, 5;
  const geometry::SurfaceMesh mesh(v, f);
  REQUIRE(mesh.face_normals().row(1).dot(n1.transpose()) == Approx(1.0));
  Eigen::VectorXd depth(2);
  depth << depth0, depth1;
  Eigen::MatrixX3d mid(2, 3);
  mid.row(0) << 1.0 / 3.0, 1.0 / 3.0, 1.0;
  mid.row(1) = mid.row(0);
  mid(1, 0) += offset;
  const Eigen::Array<bool, Eigen::Dynamic, 1> all = Eigen::Array<bool, 2, 1>::Constant(true);
  return analysis::mid_surface_pairs(mesh, mid, depth, all, all);
}

}  // namespace

TEST_CASE("mid-surface pairs: skins more than 18° from opposite are not paired") {
  const double degree = M_PI / 180.0;
  // 17° from opposite (163° apart): paired, separation along the bisector.
  const analysis::MidSurfacePairs near = two_skins(17 * degree, 1.0, 1.0);
  CHECK(near.partner(0) == 1);
  CHECK(near.partner(1) == 0);
  CHECK(near.thickness(0) == Approx(2.0 * std::cos(8.5 * degree)).epsilon(1e-9));
  // 19° (161° apart): not paired.
  const analysis::MidSurfacePairs far = two_skins(19 * degree, 1.0, 1.0);
  CHECK(far.partner(0) == -1);
  CHECK(far.partner(1) == -1);
}

TEST_CASE("mid-surface pairs: the separation must agree with the depths within a factor 2") {
  // Separation 2; the depths add to 2/0.55 and 2/0.45 (below half the separation's
  // inverse: kept / dropped), and to 2·0.55 and 2·0.45.
  CHECK(two_skins(0.0, 1.0, 2.0 / 0.55 - 1.0).partner(0) == 1);
  CHECK(two_skins(0.0, 1.0, 2.0 / 0.45 - 1.0).partner(0) == -1);
  CHECK(two_skins(0.0, 0.55, 0.55).partner(0) == 1);
  CHECK(two_skins(0.0, 0.45, 0.45).partner(0) == -1);
  CHECK(two_skins(0.0, 0.55, 0.55).thickness(0) == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("mid-surface pairs: the partner's mid-surface point within half the depth and two edges") {
  // Face 0 (area 1/2, edge √(4A/√3) = 1.0746) reaches up to ½·1 + 2·1.0746 = 2.649 from its
  // mid-surface point, face 1 (area 0.72, edge 1.2894) up to ½·1 + 2·1.2894 = 3.079.
  const analysis::MidSurfacePairs within = two_skins(0.0, 1.0, 1.0, 2.6);
  CHECK(within.partner(0) == 1);
  CHECK(within.partner(1) == 0);
  const analysis::MidSurfacePairs beyond = two_skins(0.0, 1.0, 1.0, 2.7);
  CHECK(beyond.partner(0) == -1);
  CHECK(beyond.partner(1) == 0);
  // The depth's share: with depths of 2 (separation 2 still within the factor 2 of 4), face 0
  // reaches 1 + 2.149 = 3.149.
  CHECK(two_skins(0.0, 2.0, 2.0, 3.1).partner(0) == 1);
  CHECK(two_skins(0.0, 2.0, 2.0, 3.2).partner(0) == -1);
}
