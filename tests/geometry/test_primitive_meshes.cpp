#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>

#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape::geometry;

namespace {
// Every edge of a closed, consistently oriented surface is used exactly once in each
// direction.
bool closed_and_consistent(const SurfaceMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{mesh.faces()(f, k), mesh.faces()(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    auto twin = directed.find({edge.second, edge.first});
    if (twin == directed.end() || twin->second != 1) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("geodesic sphere: counts, closedness, outward orientation, convergence of volume") {
  constexpr double pi = std::numbers::pi;
  double previous_error = 1.0;
  for (int n : {2, 4, 8}) {
    const auto mesh = make_geodesic_sphere(1.5, n);
    CHECK(mesh.num_faces() == 20 * n * n);
    CHECK(mesh.num_vertices() == 10 * n * n + 2);
    CHECK(closed_and_consistent(mesh));
    const double exact = 4.0 / 3.0 * pi * 1.5 * 1.5 * 1.5;
    const double error = std::abs(mesh.signed_volume() - exact) / exact;
    CHECK(mesh.signed_volume() > 0.0);
    // Inscribed polyhedra converge in volume at second order: halving h quarters the error.
    CHECK(error < previous_error / 3.5);
    previous_error = error;
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
      CHECK(mesh.vertices().row(v).norm() == Approx(1.5).epsilon(1e-14));
  }
  CHECK(make_geodesic_sphere(1.0, geodesic_frequency_for_edge(1.0, 0.1)).max_edge_length() <= 0.1);
}

TEST_CASE("box: closed, outward, exact volume and area, edge bound") {
  const auto mesh = make_box(Eigen::Vector3d(-2, -2, -0.15), Eigen::Vector3d(2, 2, 0.15), 0.1);
  CHECK(closed_and_consistent(mesh));
  CHECK(mesh.signed_volume() == Approx(4.0 * 4.0 * 0.3).epsilon(1e-12));
  CHECK(mesh.area() == Approx(2 * 16.0 + 4 * 4.0 * 0.3).epsilon(1e-12));
  CHECK(mesh.max_edge_length() <= 0.1 * std::sqrt(2.0) + 1e-12);
}

TEST_CASE("cylinder: closed, outward, volume converges to πr²L") {
  constexpr double pi = std::numbers::pi;
  const auto coarse = make_cylinder(0.3, 4.0, 0.1);
  const auto fine = make_cylinder(0.3, 4.0, 0.05);
  CHECK(closed_and_consistent(coarse));
  CHECK(closed_and_consistent(fine));
  const double exact = pi * 0.09 * 4.0;
  CHECK(coarse.signed_volume() > 0.0);
  CHECK(std::abs(fine.signed_volume() - exact) < std::abs(coarse.signed_volume() - exact));
  CHECK(std::abs(fine.signed_volume() - exact) / exact < 0.01);
}

TEST_CASE("spherical shell: inner sphere faces the cavity, volume is the difference") {
  constexpr double pi = std::numbers::pi;
  const auto shell = make_spherical_shell(0.7, 1.0, 16, 16);
  CHECK(closed_and_consistent(shell));
  const double exact = 4.0 / 3.0 * pi * (1.0 - 0.343);
  CHECK(shell.signed_volume() == Approx(exact).epsilon(0.01));
  // Inner faces (the second half) have normals pointing towards the centre.
  const Eigen::Index half = shell.num_faces() / 2;
  for (Eigen::Index f = half; f < shell.num_faces(); ++f)
    CHECK(shell.face_normals().row(f).dot(shell.face_centroids().row(f)) < 0.0);
}

TEST_CASE("hollow box: the cavity faces inward, volume and area are exact, bad walls refused") {
  const Eigen::Vector3d half(0.6, 0.5, 0.45);
  const auto box = make_hollow_box(half, 0.3, 0.1);
  CHECK(closed_and_consistent(box));
  const Eigen::Vector3d inner = half - Eigen::Vector3d::Constant(0.3);
  CHECK(box.signed_volume() == Approx(8.0 * (half.prod() - inner.prod())).epsilon(1e-12));
  const auto area = [](const Eigen::Vector3d& h) { return 8.0 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x()); };
  CHECK(box.area() == Approx(area(half) + area(inner)).epsilon(1e-12));
  // The outer box comes first; the cavity's faces (the rest) have normals towards the centre.
  const Eigen::Index outer = make_box(-half, half, 0.1).num_faces();
  for (Eigen::Index f = outer; f < box.num_faces(); ++f)
    CHECK(box.face_normals().row(f).dot(box.face_centroids().row(f)) < 0.0);
  CHECK_THROWS_AS(make_hollow_box(half, 0.0, 0.1), bemshape::InputError);
  CHECK_THROWS_AS(make_hollow_box(half, 0.45, 0.1), bemshape::InputError);
}
