// The closed-form Laplace potentials of a triangle against the brute-force adaptive reference
// (tests/bem/panel_reference.hpp, taken to 1e-10 so that the test takes seconds) from a
// twentieth of a diameter to twenty diameters, against the solid angle of a cube's faces, and
// against the polar scheme in the panel's plane.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/laplace_triangle_potentials.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/polar_quadrature.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/bem/panel_reference.hpp"

using namespace bemshape;
using bem::laplace_triangle_potentials;
using Eigen::Vector3d;

namespace {

/// Error of `value` against `reference`, relative to the reference or, where that is small by
/// cancellation, to a millionth of the entry's near-field magnitude.
double error(double value, double reference, double magnitude) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-6 * magnitude);
}
double error(const Vector3d& value, const Vector3d& reference, double magnitude) {
  return (value - reference).norm() / std::max(reference.norm(), 1e-6 * magnitude);
}

}  // namespace

TEST_CASE("Laplace triangle potentials: V, K and their gradients within 1e-9 of the adaptive reference") {
  const std::vector<double> distances = {0.05, 0.3, 1.0, 3.0, 20.0};
  const std::vector<Vector3d> directions = testing::target_directions(6, 7);
  double worst_single = 0.0, worst_double = 0.0, worst_grad_single = 0.0, worst_grad_double = 0.0;
  for (const bem::Panel& panel : testing::rule_test_panels()) {
    const testing::NearFieldMagnitudes mag = testing::near_field_magnitudes(panel, 0.0);
    // From the centroid and from a corner and an edge's middle (targets near the edges).
    const std::vector<Vector3d> origins = {panel.centroid, panel.corners[1],
                                           0.5 * (panel.corners[0] + panel.corners[2])};
    for (const Vector3d& origin : origins)
      for (double distance : distances)
        for (const Vector3d& direction : directions) {
          const Vector3d x = origin + distance * panel.diameter * direction;
          if (std::abs((x - panel.corners[0]).dot(panel.normal)) < 1e-3 * panel.diameter)
            continue;  // in-plane targets: the next test case
          const testing::ReferenceIntegrals ref =
              testing::reference_panel_integrals(0.0, panel, x, true, 1e-10);
          const bem::PanelIntegrals p = laplace_triangle_potentials(panel, x, true);
          CAPTURE(distance, x.transpose());
          worst_single = std::max(worst_single, error(p.single_layer, ref.single_layer, mag.single_layer));
          worst_double = std::max(worst_double, error(p.double_layer, ref.double_layer, mag.double_layer));
          worst_grad_single = std::max(worst_grad_single, error(p.single_layer_gradient, ref.single_layer_gradient, mag.single_layer_gradient));
          worst_grad_double = std::max(worst_grad_double, error(p.double_layer_gradient, ref.double_layer_gradient, mag.double_layer_gradient));
        }
  }
  WARN("worst errors: V " << worst_single << ", K " << worst_double << ", grad V " << worst_grad_single
                          << ", grad K " << worst_grad_double);
  CHECK(worst_single < 1e-9);
  CHECK(worst_double < 1e-9);
  CHECK(worst_grad_single < 1e-9);
  CHECK(worst_grad_double < 1e-9);
}

TEST_CASE("Laplace triangle potentials: a cube's faces subtend 4π from inside and nothing from outside") {
  const geometry::SurfaceMesh cube =
      geometry::make_box(Vector3d::Zero(), Vector3d(1.0, 2.0, 3.0), 0.7);
  const std::vector<bem::Panel> panels = bem::make_panels(cube);
  for (const Vector3d& x : {Vector3d(0.5, 1.0, 1.5), Vector3d(0.05, 1.9, 0.1), Vector3d(1.3, 1.0, 1.5),
                            Vector3d(-2.0, 5.0, 7.0)}) {
    const bool inside = x.x() > 0 && x.x() < 1 && x.y() > 0 && x.y() < 2 && x.z() > 0 && x.z() < 3;
    double k = 0.0;
    Vector3d grad_k = Vector3d::Zero();
    for (const bem::Panel& panel : panels) {
      const bem::PanelIntegrals p = laplace_triangle_potentials(panel, x, true);
      k += p.double_layer;
      grad_k += p.double_layer_gradient;
    }
    CAPTURE(x.transpose());
    // K sums to −1 inside an outward surface and 0 outside, constants whose gradients vanish.
    CHECK(k == Approx(inside ? -1.0 : 0.0).margin(1e-13));
    CHECK(grad_k.norm() < 1e-12);
  }
  // A face of a cube seen from its centre: Ω = 4π/6, K = 1/6 (the two triangles of the face).
  const std::vector<bem::Panel> face = {
      bem::make_panel(Vector3d(-1, -1, 1), Vector3d(1, -1, 1), Vector3d(1, 1, 1)),
      bem::make_panel(Vector3d(-1, -1, 1), Vector3d(1, 1, 1), Vector3d(-1, 1, 1))};
  double k = 0.0;
  for (const bem::Panel& panel : face) k += laplace_triangle_potentials(panel, Vector3d::Zero(), false).double_layer;
  CHECK(k == Approx(-1.0 / 6.0).epsilon(1e-14));  // below the face: h < 0
}

TEST_CASE("Laplace triangle potentials: in the panel's plane as the polar scheme takes them") {
  for (const bem::Panel& panel : testing::rule_test_panels()) {
    const Vector3d in_plane = panel.tangent1;
    for (const Vector3d& x : {Vector3d(panel.centroid), Vector3d(panel.centroid + 0.1 * panel.diameter * panel.tangent2),
                              Vector3d(panel.centroid + 2.0 * panel.diameter * in_plane),
                              Vector3d(panel.corners[0] - 0.3 * panel.diameter * (in_plane + 0.37 * panel.tangent2))}) {
      const bem::PanelIntegrals p = laplace_triangle_potentials(panel, x, true);
      const bem::PanelIntegrals q = bem::polar_panel_integrals(bem::LaplaceKernel{}, panel, x, true);
      CAPTURE(x.transpose());
      CHECK(p.single_layer == Approx(q.single_layer).epsilon(1e-12));
      CHECK(p.double_layer == 0.0);
      CHECK((p.single_layer_gradient - q.single_layer_gradient).norm() <= 1e-10 * q.single_layer_gradient.norm() + 1e-14);
      CHECK((p.double_layer_gradient - q.double_layer_gradient).norm() <= 1e-9 * q.double_layer_gradient.norm() + 1e-12);
    }
  }
}
