// Identities of the Galerkin boundary operators (docs/theory.md, section 2) on closed
// polyhedra, where they hold exactly up to quadrature.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <numbers>
#include <vector>

#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;
using namespace bemshape::bem;

namespace {
Eigen::MatrixXd assemble(const std::vector<Panel>& panels, auto kernel, bool double_layer) {
  const GalerkinOperators op(kernel, panels);
  const auto n = static_cast<Eigen::Index>(panels.size());
  Eigen::MatrixXd m(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto e = op.entry(j, k);
      m(j, k) = double_layer ? e.double_layer : e.single_layer;
    }
  return m;
}

/// On a 2×2 square meshed with edges of 0.1, the row sums of Vκ of the panels whose corners
/// are all further than 20/κ from the border, which see an infinite plane up to e^{−20},
/// divided by their areas are 1/(2κ) within `tolerance`; those panels are more than
/// `min_kappa_diameter`/κ across.
void check_plane_row_sums(double kappa, double tolerance, double min_kappa_diameter = 0.0) {
  const auto box = geometry::make_box(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 0), 0.1);
  const auto panels = make_panels(box);
  const GalerkinOperators op(YukawaKernel{kappa}, panels);
  int checked = 0;
  for (Eigen::Index j = 0; j < box.num_faces(); j += 7) {
    const Panel& panel = panels[size_t(j)];
    double border = 0.0;  // the largest |x| or |y| of a corner
    for (const auto& corner : panel.corners) border = std::max(border, corner.head<2>().cwiseAbs().maxCoeff());
    if (panel.centroid.z() < -1e-12 || border > 1.0 - 20.0 / kappa) continue;
    REQUIRE(kappa * panels[size_t(j)].diameter > min_kappa_diameter);
    double sum = 0.0;
    for (Eigen::Index k = 0; k < box.num_faces(); ++k) sum += op.entry(j, k).single_layer;
    CHECK(sum / box.face_areas()(j) == Approx(1.0 / (2.0 * kappa)).epsilon(tolerance));
    ++checked;
  }
  CHECK(checked > 20);
}
}  // namespace

TEST_CASE("Laplace double layer of the unit density is -1/2 on a closed surface (K0[1] = -1/2)") {
  for (const auto& mesh : {geometry::make_geodesic_sphere(0.5, 4),
                           geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.5, 0.3), 0.2)}) {
    const auto panels = make_panels(mesh);
    const Eigen::MatrixXd k0 = assemble(panels, LaplaceKernel{}, true);
    const Eigen::VectorXd row_sums = k0.rowwise().sum();
    for (Eigen::Index j = 0; j < row_sums.size(); ++j)
      CHECK(row_sums(j) / mesh.face_areas()(j) == Approx(-0.5).margin(2e-3));
    // Area-weighted: the graded outer rules (bem/operators/galerkin_operators.hpp) integrate each
    // panel's far-field potential to about 1e-3; a sign or jump error would show as O(1).
    CHECK(row_sums.sum() / mesh.area() == Approx(-0.5).margin(1e-3));
  }
}

TEST_CASE("Laplace single layer of the unit density approaches R on a sphere (V0[1] = R)") {
  double previous = 1.0;
  for (int n : {2, 4, 8}) {
    const auto mesh = geometry::make_geodesic_sphere(0.5, n);
    const Eigen::MatrixXd v0 = assemble(make_panels(mesh), LaplaceKernel{}, false);
    const double mean = v0.sum() / mesh.area();  // area-weighted mean of V0[1] over Γ
    const double error = std::abs(mean - 0.5) / 0.5;
    CHECK(error < previous / 2.5);  // the inscribed polyhedron converges at second order
    previous = error;
  }
  CHECK(previous < 5e-3);
}

TEST_CASE("Laplace single layer is symmetric (Galerkin)") {
  const auto mesh = geometry::make_geodesic_sphere(1.0, 3);
  const Eigen::MatrixXd v0 = assemble(make_panels(mesh), LaplaceKernel{}, false);
  // The outer rules are graded by distance, so symmetry holds to their accuracy (~1e-4).
  CHECK((v0 - v0.transpose()).norm() / v0.norm() < 3e-4);
}

TEST_CASE("Yukawa single layer of the unit density on a large flat panel tends to 1/(2κ)") {
  // κ = 50: panels 7/κ across, whose near pairs that do not touch take the 12-point outer rule.
  check_plane_row_sums(50.0, 1e-6);
}

TEST_CASE("Yukawa single layer on a flat panel at kappa*diameter 21 (the 6-point near rule) "
          "tends to 1/(2κ)") {
  // κ = 150: panels 21/κ across, whose near pairs that do not touch take the 6-point outer
  // rule (GalerkinOperators::near_outer_rule).
  check_plane_row_sums(150.0, 1e-7, 12.0);
}

TEST_CASE("Yukawa single layer on a flat panel at kappa*diameter 42 and 71 tends to 1/(2κ)") {
  // κ = 300 and 500: panels 42/κ and 71/κ across, where the row is mostly its touching
  // pairs, whose rules integrate along x − y in closed form.
  check_plane_row_sums(300.0, 5e-8, 40.0);
  check_plane_row_sums(500.0, 5e-8, 70.0);
}

TEST_CASE("Yukawa near pairs: a small test panel a gap of 1-6 diameters from a large trial "
          "panel takes the fewer outer points of near_outer_rule(test, trial)") {
  // A trial panel about 1 across and a test panel 0.5 across (κ·diameter 4-8 for the test panel,
  // where the rule of near_outer_rule(test) alone has 12 points), beside the trial panel in its
  // plane and tilted above it, at gaps g of 1-6 test diameters. The reference: the 12-point
  // rule on 16 sub-triangles. Errors against the unattenuated magnitudes |T_j||T_k|/(4πr) (V)
  // and |T_j||T_k|(1 + κr)/(4πr²) (K), r the distance of the centroids (YukawaAttenuation).
  const Panel trial = make_panel(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                 Eigen::Vector3d(0.3, 0.9, 0));
  const auto small_panel = [](const Eigen::Vector3d& centre, const Eigen::Vector3d& normal) {
    const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.normalized().cross(u);
    const double r = 0.5 / std::sqrt(3.0);  // circumradius of an equilateral triangle of side 0.5
    return make_panel(centre + r * u, centre + r * (-0.5 * u + 0.866025403784 * w),
                      centre + r * (-0.5 * u - 0.866025403784 * w));
  };
  const std::vector<Panel> panels{trial};
  double worst = 0.0, worst_three_point_near = 0.0;
  int checked = 0;
  for (const double kappa : {8.0, 12.0, 16.0}) {
    const GalerkinOperators op(YukawaKernel{kappa}, panels);
    for (const double gap_in_diameters : {1.0, 1.5, 2.0, 3.0, 4.0, 6.0}) {
      for (int placement = 0; placement < 2; ++placement) {
        // Beside the edge from (1, 0) to (0.3, 0.9) in the plane, or above the panel, tilted.
        const Eigen::Vector3d out = Eigen::Vector3d(0.9, 0.7, 0).normalized();
        const Eigen::Vector3d foot = placement == 0 ? Eigen::Vector3d(0.65, 0.45, 0)
                                                    : Eigen::Vector3d(0.45, 0.3, 0);
        const Eigen::Vector3d direction = placement == 0 ? out : Eigen::Vector3d(0.2, 0.1, 1).normalized();
        const Eigen::Vector3d normal = placement == 0 ? Eigen::Vector3d(0, 0, 1)
                                                      : Eigen::Vector3d(1, -0.5, 0.7);
        Panel test = small_panel(foot, normal);
        // Move the test panel out until its gap, as near_outer_rule measures it, is reached.
        const double target = gap_in_diameters * test.diameter;
        for (int it = 0; it < 60; ++it) {
          const double gap = distance_to_panel(trial, test.centroid) - test.radius;
          if (std::abs(gap - target) < 1e-9) break;
          test = small_panel(test.centroid + (target - gap) * direction, normal);
        }
        if (GalerkinOperators<YukawaKernel>::separation_ratio(test, trial) >=
            OuterRuleThresholds::near_ratio)
          continue;
        const double r = (test.centroid - trial.centroid).norm();
        const double v_scale = test.area * trial.area / (4.0 * std::numbers::pi * r);
        const double k_scale = v_scale * (1.0 + kappa * r) / r;
        const auto ref = op.outer_rule_entry(test, trial, 2, symmetric_triangle_rule(6));
        const auto e = op.outer_rule_entry(test, trial, 0, op.near_outer_rule(test, trial));
        const double error = std::max(std::abs(e.single_layer - ref.single_layer) / v_scale,
                                      std::abs(e.double_layer - ref.double_layer) / k_scale);
        CAPTURE(kappa, gap_in_diameters, placement, error);
        CHECK(error < 1e-6);
        worst = std::max(worst, error);
        ++checked;
        if (gap_in_diameters == 1.0) {
          const auto three = op.outer_rule_entry(test, trial, 0, symmetric_triangle_rule(2));
          worst_three_point_near =
              std::max({worst_three_point_near,
                        std::abs(three.single_layer - ref.single_layer) / v_scale,
                        std::abs(three.double_layer - ref.double_layer) / k_scale});
        }
      }
    }
  }
  CAPTURE(worst, worst_three_point_near);
  CHECK(checked >= 24);
  // The check can fail: the 3-point rule at one diameter is far outside it.
  CHECK(worst_three_point_near > 1e-5);
}

TEST_CASE("Galerkin entries are invariant under rotation and translation") {
  const auto mesh = geometry::make_geodesic_sphere(0.5, 2);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const auto moved = geometry::transformed(mesh, r, Eigen::Vector3d(3.0, -1.0, 7.0));
  const auto a = make_panels(mesh), b = make_panels(moved);
  for (const bool dl : {false, true}) {
    const Eigen::MatrixXd ka = assemble(a, YukawaKernel{20.0}, dl), kb = assemble(b, YukawaKernel{20.0}, dl);
    CHECK((ka - kb).norm() / ka.norm() < 1e-10);
    const Eigen::MatrixXd la = assemble(a, LaplaceKernel{}, dl), lb = assemble(b, LaplaceKernel{}, dl);
    CHECK((la - lb).norm() / la.norm() < 1e-10);
  }
}

TEST_CASE("Yukawa attenuated entries: the trial panel's collapsed Gauss rule is within the "
          "attenuation budget of the accurate panel integral") {
  // Attenuated pairs (e^{−κ·gap} < 1e−3) take the test panel's centroid as the outer rule,
  // like the far pairs (OuterRuleThresholds: the outer rule is set by the discretisation
  // error), and a collapsed Gauss rule on the trial panel whose size attenuated_rule_points
  // picks for an error below 1e−9 of the unattenuated magnitude |T_j||T_k|/(4π·r). The
  // reference is integrate_panel at the same centroid (1e−8 relative accuracy). Sphere
  // panels at κ·h = 3, the default element size.
  const auto sphere = geometry::make_geodesic_sphere(0.5, 8);
  const auto panels = make_panels(sphere);
  const double edge = std::sqrt(4.0 * sphere.face_areas().mean() / std::sqrt(3.0));
  const double kappa = 3.0 / edge;
  const YukawaKernel kernel{kappa};
  const GalerkinOperators op(kernel, panels);
  const Panel& test = panels[0];
  int checked = 0;
  for (size_t k = 1; k < panels.size(); k += 3) {
    const Panel& trial = panels[k];
    const double distance = (test.centroid - trial.centroid).norm();
    const double gap = distance - test.radius - trial.radius;
    const double attenuation = std::exp(-kappa * gap);
    const double ratio = distance / std::max(test.diameter, trial.diameter);
    if (gap <= 0.0 || attenuation >= YukawaAttenuation::cheap_rule || ratio < 1.5 ||
        attenuation < YukawaAttenuation::negligible ||
        attenuated_rule_points(attenuation, kappa * trial.diameter, ratio) == 0)
      continue;  // not in the attenuated class
    const auto cheap = op.entry(0, Eigen::Index(k));
    const PanelIntegrals accurate = integrate_panel(kernel, trial, test.centroid);
    const double unattenuated = test.area * trial.area * YukawaKernel::inv_four_pi / distance;
    CHECK(std::abs(cheap.single_layer - test.area * accurate.single_layer) <= 1e-9 * unattenuated);
    CHECK(std::abs(cheap.double_layer - test.area * accurate.double_layer) <= 1e-9 * unattenuated);
    CHECK(cheap.single_layer > 0.0);
    ++checked;
  }
  CHECK(checked > 20);
}

TEST_CASE("Touching pairs: tabulated entries equal computed ones, V[j, k] = V[k, j] exactly") {
  for (const auto& mesh : {geometry::make_geodesic_sphere(0.5, 4),
                           geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.5, 0.3), 0.2)}) {
    const auto panels = make_panels(mesh);
    const auto n = static_cast<Eigen::Index>(panels.size());
    const auto check = [&](auto kernel) {
      const GalerkinOperators computed(kernel, panels);
      GalerkinOperators tabulated(kernel, panels);
      tabulated.tabulate_touching_pairs();
      int touching = 0;
      for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index k = 0; k < n; ++k) {
          if (!computed.touching(panels[size_t(j)], panels[size_t(k)])) continue;
          ++touching;
          const auto a = computed.entry(j, k), b = tabulated.entry(j, k), t = computed.entry(k, j);
          REQUIRE(a.single_layer == b.single_layer);
          REQUIRE(a.double_layer == b.double_layer);
          REQUIRE(a.single_layer == t.single_layer);
        }
      // Every panel touches itself and at least its three edge neighbours.
      CHECK(touching >= 4 * n);
      // Pairs that do not touch are computed as before (the table holds touching pairs only).
      CHECK(tabulated.entry(0, n - 1).single_layer == computed.entry(0, n - 1).single_layer);
    };
    check(LaplaceKernel{});
    check(YukawaKernel{20.0});
  }
}
