#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/mesh_size_field.hpp"
#include "geometry/surface_creases.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

/// A plate [0, 120] × [0, 80] × [0, t] and the field of h0 = 3.6 (h_f = 0.3·h0).
struct Plate {
  SurfaceMesh mesh;
  SurfaceCreases creases;
  SizeFieldParameters parameters;
  explicit Plate(double t) : mesh(make_box_solid(Eigen::Vector3d::Zero(), Eigen::Vector3d(120, 80, t))) {
    creases = find_surface_creases(mesh);
    parameters.fine_edge = 1.08;
    parameters.max_edge = 7.2;
    parameters.gradation = 1.4;
    parameters.thin_wall = 3.6;
    parameters.sample_spacing = 1.8;
  }
};

/// A random point of the mesh's surface (uniform over each face, faces by area).
Eigen::Vector3d random_surface_point(const SurfaceMesh& mesh, std::mt19937& rng) {
  std::discrete_distribution<Eigen::Index> face(mesh.face_areas().data(),
                                                mesh.face_areas().data() + mesh.num_faces());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Index f = face(rng);
  double r = u(rng), s = u(rng);
  if (r + s > 1.0) {
    r = 1.0 - r;
    s = 1.0 - s;
  }
  return mesh.corner(f, 0) + r * (mesh.corner(f, 1) - mesh.corner(f, 0)) +
         s * (mesh.corner(f, 2) - mesh.corner(f, 0));
}

/// A 48-facet rod of radius 10 and length 40 read as a smooth surface (facet angles of 7.5°
/// below the 15° smooth angle): its axial facet edges, of width w and turning θ, are
/// curvature sources; h_f 0.5, curvature ratio 0.2, no maximum in the way.
struct SmoothedRod {
  SurfaceMesh mesh = make_faceted_cylinder(Eigen::Vector2d(0, 0), 10.0, 0.0, 40.0, 48);
  double theta = 2.0 * std::numbers::pi / 48;
  double w = 20.0 * std::sin(std::numbers::pi / 48);
  CreaseOptions options;
  SizeFieldParameters parameters;
  SmoothedRod() {
    options.smooth_angle_degrees = 15.0;
    options.chord_tolerance = 1.0;
    options.min_chord = 0.5;
    parameters.fine_edge = 0.5;
    parameters.max_edge = 50.0;
    parameters.curvature_ratio = 0.2;
  }
  MeshSizeField field() const {
    return MeshSizeField(mesh, find_surface_creases(mesh, options), parameters);
  }
};

}  // namespace

TEST_CASE("size field on a plate: h_f on a crease, growing with g − 1 away from it, the wall far from it") {
  const Plate plate(4.0);
  const MeshSizeField field(plate.mesh, plate.creases, plate.parameters);
  // On the edge x = 0 of the top face.
  const auto [on_crease, why] = field.size_and_reason(Eigen::Vector3d(0, 40, 4));
  CHECK(on_crease == Approx(1.08));
  CHECK(why == SizeReason::crease);
  // 3 from it on the top face: the crease's cone 1.08 + 0.4·3 (the bottom edge is 5 away).
  const auto [near, near_why] = field.size_and_reason(Eigen::Vector3d(3, 40, 4));
  CHECK(near == Approx(1.08 + 0.4 * 3));
  CHECK(near_why == SizeReason::crease);
  // Far from every crease the wall (4 thick, c_t = 1) bounds it: 4 plus at most the cone over
  // the distance to the nearest sample (half a spacing's diagonal, ≤ 1.8/√2).
  const auto [centre, centre_why] = field.size_and_reason(Eigen::Vector3d(60, 40, 4));
  CHECK(centre >= 4.0 - 1e-12);
  CHECK(centre <= 4.0 + 0.4 * 1.8 / std::sqrt(2.0));
  CHECK(centre_why == SizeReason::wall_thickness);
  CHECK(field.summary().sources[static_cast<std::size_t>(SizeReason::thin_wall)] == 0);
}

TEST_CASE("size field: without wall sources the plate's centre is the nearest crease's cone") {
  Plate plate(4.0);
  plate.parameters.thin_wall = 0.0;
  plate.parameters.max_edge = 100.0;
  const MeshSizeField field(plate.mesh, plate.creases, plate.parameters);
  // The nearest creases are the long top edges, 40 away.
  CHECK(field.size(Eigen::Vector3d(60, 40, 4)) == Approx(1.08 + 0.4 * 40));
  plate.parameters.max_edge = 7.2;
  const MeshSizeField capped(plate.mesh, plate.creases, plate.parameters);
  const auto [h, why] = capped.size_and_reason(Eigen::Vector3d(60, 40, 4));
  CHECK(h == 7.2);
  CHECK(why == SizeReason::maximum);
}

TEST_CASE("size field: the gradation bound |h(x) − h(y)| ≤ (g − 1)|x − y| holds everywhere") {
  const Plate plate(4.0);
  const MeshSizeField field(plate.mesh, plate.creases, plate.parameters);
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d x = random_surface_point(plate.mesh, rng);
    // Pairs near each other (where the bound bites) and far apart.
    const Eigen::Vector3d y = i % 2 ? random_surface_point(plate.mesh, rng)
                                    : Eigen::Vector3d(x + 0.5 * Eigen::Vector3d::Random());
    const double hx = field.size(x), hy = field.size(y);
    CHECK(std::abs(hx - hy) <= 0.4 * (x - y).norm() * (1 + 1e-12) + 1e-12);
    CHECK(hx >= 1.08 - 1e-12);
    CHECK(hx <= 7.2);
  }
}

TEST_CASE("size field: a wall thinner than t_thin gets h_f") {
  const Plate plate(1.0);  // 1 < t_thin = h0 = 3.6
  const MeshSizeField field(plate.mesh, plate.creases, plate.parameters);
  const auto [h, why] = field.size_and_reason(Eigen::Vector3d(60, 40, 1));
  CHECK(h >= 1.08);
  CHECK(h <= 1.08 + 0.4 * 1.8 / std::sqrt(2.0));
  CHECK(why == SizeReason::thin_wall);
}

TEST_CASE("size field: creases closer than h_f/c_l bound the size between them") {
  // A slab 0.5 thick: the side faces' two creases are 0.5 apart, so their spacing asks for
  // c_l·0.5 = 0.75 < h_f.
  Plate plate(0.5);
  plate.parameters.thin_wall = 0.0;
  const MeshSizeField field(plate.mesh, plate.creases, plate.parameters);
  const auto [h, why] = field.size_and_reason(Eigen::Vector3d(60, 0, 0.25));
  CHECK(why == SizeReason::crease_spacing);
  CHECK(h <= kCreaseSpacingEdgeRatio * 0.5 + 0.4 * 0.25);
  CHECK(h >= 0.75 * kCreaseSpacingEdgeRatio * 0.5);
}

TEST_CASE("size field on a smoothed rod: curvature c_ρ·ρ, or the chord limit where smaller") {
  SmoothedRod rod;
  // A point on an axial facet edge, halfway up (the rims' creases are 20 away).
  const Eigen::Vector3d on_edge(10.0, 0.0, 20.0);
  {
    const auto [h, why] = rod.field().size_and_reason(on_edge);
    CHECK(h == Approx(0.2 * rod.w / rod.theta));
    CHECK(why == SizeReason::curvature);
  }
  // δ for a chord of 1 crossing one facet edge: sag = h·θ/4.
  rod.options.chord_tolerance = rod.theta / 4.0;
  {
    const auto [h, why] = rod.field().size_and_reason(on_edge);
    CHECK(h == Approx(1.0));
    CHECK(why == SizeReason::chord);
  }
}

TEST_CASE("size field: constant field and refused parameters") {
  const MeshSizeField constant(2.5);
  const auto [h, why] = constant.size_and_reason(Eigen::Vector3d(1, 2, 3));
  CHECK(h == 2.5);
  CHECK(why == SizeReason::maximum);
  CHECK_THROWS_AS(MeshSizeField(0.0), InputError);
  Plate plate(4.0);
  plate.parameters.fine_edge = 10.0;  // above h_max
  CHECK_THROWS_AS(MeshSizeField(plate.mesh, plate.creases, plate.parameters), InputError);
  plate.parameters.fine_edge = 1.0;
  plate.parameters.gradation = 1.0;
  CHECK_THROWS_AS(MeshSizeField(plate.mesh, plate.creases, plate.parameters), InputError);
}

TEST_CASE("size field on a smoothed rod: curvature sources grow gently within their size, at g beyond") {
  // The axial facet edges of a 48-facet rod of radius 10 are curvature sources of
  // c_ρ·ρ = 0.2·w/θ = 2.0. With g = 2 and a curvature gradation of 1.4, a facet's middle
  // (w/2 = 0.65 from its edges) asks 2.0 + 0.4·w/2, not 2.0 + w/2; the end cap's centre,
  // 10 from the edges' ends, 2.0 + 0.4·2.0 + 1.0·(10 − 2.0).
  SmoothedRod rod;
  rod.parameters.refine_creases = false;
  rod.parameters.gradation = 2.0;
  rod.parameters.curvature_gradation = 1.4;
  const MeshSizeField field = rod.field();
  const double theta = rod.theta, w = rod.w;
  const double source = 0.2 * w / theta;
  REQUIRE(source == Approx(2.0).epsilon(0.01));
  const Eigen::Vector3d facet_middle =
      0.5 * (Eigen::Vector3d(10.0, 0.0, 20.0) +
             Eigen::Vector3d(10.0 * std::cos(theta), 10.0 * std::sin(theta), 20.0));
  const double to_edge = 0.5 * w;
  const auto [h, why] = field.size_and_reason(facet_middle);
  CHECK(why == SizeReason::curvature);
  CHECK(h == Approx(source + 0.4 * to_edge));
  const auto [h_cap, why_cap] = field.size_and_reason(Eigen::Vector3d(0.0, 0.0, 0.0));
  CHECK(why_cap == SizeReason::curvature);
  CHECK(h_cap == Approx(source + 0.4 * source + 1.0 * (10.0 - source)));
}
