#include <catch2/catch.hpp>
#include <cmath>

#include "bem/quadrature/panel.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;
using Eigen::Vector3d;

TEST_CASE("panel geometry: normal, frame, area, diameter, radius", "[panel]") {
  const bem::Panel p = bem::make_panel(Vector3d(1, 1, 1), Vector3d(4, 1, 1), Vector3d(1, 5, 1));
  CHECK((p.normal - Vector3d(0, 0, 1)).norm() < 1e-15);  // right-hand rule
  CHECK(p.area == Approx(6.0));
  CHECK(p.diameter == Approx(5.0));
  CHECK((p.centroid - Vector3d(2, 7.0 / 3.0, 1)).norm() < 1e-15);
  CHECK(p.radius == Approx((Vector3d(1, 5, 1) - p.centroid).norm()));
  CHECK(std::abs(p.tangent1.dot(p.tangent2)) < 1e-15);
  CHECK(std::abs(p.tangent1.dot(p.normal)) < 1e-15);
  CHECK((p.tangent1.cross(p.tangent2) - p.normal).norm() < 1e-15);  // right-handed frame
  CHECK((p.edge1 - Vector3d(3, 0, 0)).norm() == 0.0);
}

TEST_CASE("panel geometry: degenerate triangles are input errors", "[panel]") {
  CHECK_THROWS_AS(bem::make_panel(Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2)),
                  InputError);
}

TEST_CASE("make_panels: one outward panel per face of a closed mesh", "[panel]") {
  const auto mesh = geometry::make_geodesic_sphere(2.0, 3);
  const auto panels = bem::make_panels(mesh);
  REQUIRE(static_cast<Eigen::Index>(panels.size()) == mesh.num_faces());
  double area = 0;
  for (size_t f = 0; f < panels.size(); ++f) {
    CHECK(panels[f].normal.dot(panels[f].centroid) > 0.0);  // outward on a sphere
    CHECK(panels[f].area == Approx(mesh.face_areas()[static_cast<Eigen::Index>(f)]));
    area += panels[f].area;
  }
  CHECK(area == Approx(mesh.area()));
}
