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

TEST_CASE("distance_to_panel: above the face, beyond an edge, beyond a corner", "[panel]") {
  // The right triangle (0,0,0), (4,0,0), (0,3,0): closed forms in each region of the plane,
  // and the minimum over a fine sampling of the triangle for points all around it.
  const bem::Panel p = bem::make_panel(Vector3d(0, 0, 0), Vector3d(4, 0, 0), Vector3d(0, 3, 0));
  CHECK(bem::distance_to_panel(p, Vector3d(1, 1, 2)) == Approx(2.0));        // above the face
  CHECK(bem::distance_to_panel(p, Vector3d(1, 1, -0.5)) == Approx(0.5));     // below it
  CHECK(bem::distance_to_panel(p, Vector3d(2, -3, 4)) == Approx(5.0));       // beyond edge ab
  CHECK(bem::distance_to_panel(p, Vector3d(-2, -2, 1)) == Approx(3.0));      // beyond corner a
  CHECK(bem::distance_to_panel(p, Vector3d(4, 3, 0)) == Approx(12.0 / 5.0)); // beyond the hypotenuse
  CHECK(bem::distance_to_panel(p, Vector3d(1, 1, 0)) == 0.0);                // on the face
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double a = 0.37 * k, z = std::sin(1.3 * k);
    const Vector3d x(1.3 + 4.0 * std::cos(a), 1.0 + 4.0 * std::sin(a), 2.0 * z);
    double sampled = INFINITY;
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; i + j <= 400; ++j)
        sampled = std::min(sampled, (x - Vector3d(4.0 * i / 400, 3.0 * j / 400, 0)).norm());
    const double d = bem::distance_to_panel(p, x);
    CHECK(d <= sampled + 1e-12);  // never more than a point of the triangle
    worst = std::max(worst, sampled - d);
  }
  CHECK(worst < 0.01);  // the sampling's spacing
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
