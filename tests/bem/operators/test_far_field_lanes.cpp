// The entries computed kFarFieldLanes pairs at a time (bem/operators/far_field_lanes.hpp: the Laplace
// far field through GalerkinOperators::fill_range, the attenuated Yukawa pairs through
// fill_row) against the same entries one pair at a time (GalerkinOperators::entry): same
// rules and formulas, so they agree to rounding.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "bem/operators/far_field_lanes.hpp"
#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/triangle_quadrature.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;
using namespace bemshape::bem;

namespace {
/// Panels of one sphere of radius 0.5 (kSphere = 320 panels, diameter ≈ 0.14), at panel
/// indices [0, 320), and of two copies: 5 units away along x at [320, 640), 100 units away at
/// [640, 960). Pairs within one sphere are touching, near or use the 12- and 16-point rules;
/// pairs with the first copy use the 7-point rule (ratio ≈ 35), with the second the 3-point
/// rule (ratio > 150).
constexpr Eigen::Index kSphere = 320;
std::vector<Panel> three_spheres() {
  const auto sphere = make_panels(geometry::make_geodesic_sphere(0.5, 4));
  std::vector<Panel> panels;
  for (const double x : {0.0, 5.0, 100.0}) {
    const Eigen::Vector3d shift(x, 0.0, 0.0);
    for (const Panel& p : sphere)
      panels.push_back(make_panel(p.corners[0] + shift, p.corners[1] + shift, p.corners[2] + shift));
  }
  return panels;
}

/// |a − b| ≤ 1e−13·|b| + 1e−13·scale: rounding only (a different rule would differ by ~1e−9).
void check_same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const double scale = b.cwiseAbs().maxCoeff();
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      REQUIRE(std::abs(a(r, c) - b(r, c)) <= 1e-13 * (std::abs(b(r, c)) + scale * 1e-3));
}
}  // namespace

TEST_CASE("Far-field lanes: fill_range gives entry()'s values along a row and along columns") {
  const auto panels = three_spheres();
  const GalerkinOperators op(LaplaceKernel{}, panels);
  const auto n = static_cast<Eigen::Index>(panels.size());
  Eigen::MatrixXd v_ref(n, n), k_ref(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto e = op.entry(j, k);
      v_ref(j, k) = e.single_layer;
      k_ref(j, k) = e.double_layer;
    }

  SECTION("one row at a time (vectorised over trial panels), with a ragged start and end") {
    for (const Eigen::Index j : {Eigen::Index(0), Eigen::Index(17), n / 2 + 5, n - 1}) {
      const Eigen::Index begin = 3, end = n - 2;
      Eigen::MatrixXd v(1, end - begin), k(1, end - begin);
      op.fill_range(j, j + 1, begin, end, v, k);
      check_same(v, v_ref.block(j, begin, 1, end - begin));
      check_same(k, k_ref.block(j, begin, 1, end - begin));
    }
  }
  SECTION("blocks of rows (vectorised over test panels per column)") {
    for (const Eigen::Index column : {Eigen::Index(100), kSphere + 100, 2 * kSphere + 100}) {
      const Eigen::Index begin = 5, end = n - 3;
      Eigen::MatrixXd v(end - begin, 40), k(end - begin, 40);
      op.fill_range(begin, end, column, column + 40, v, k);
      check_same(v, v_ref.block(begin, column, end - begin, 40));
      check_same(k, k_ref.block(begin, column, end - begin, 40));
    }
  }
}

TEST_CASE("Far-field lanes: computed for far pairs with each lane's own rule and near pairs left out") {
  const auto panels = three_spheres();
  const PanelArrays arrays(panels);
  const GalerkinOperators op(LaplaceKernel{}, panels);
  FarFieldEntries lanes;
  // Panel 0 against 8 panels of each copy: one rule (7 and 3 points), computed.
  for (const Eigen::Index first : {kSphere + 40, 2 * kSphere + 40}) {
    REQUIRE(laplace_far_field_lanes(PanelLanes::repeated(arrays, 0),
                                    PanelLanes::consecutive(arrays, first),
                                    OuterRuleThresholds::far_ratio, lanes) == 0xffu);
    for (Eigen::Index l = 0; l < kFarFieldLanes; ++l) {
      const auto e = op.entry(0, first + l);
      CHECK(lanes.single_layer(l) == Approx(e.single_layer).epsilon(1e-13));
      CHECK(lanes.double_layer(l) == Approx(e.double_layer).epsilon(1e-13));
    }
  }
  // The other orientation: 8 test panels of the first copy, one trial panel.
  REQUIRE(laplace_far_field_lanes(PanelLanes::consecutive(arrays, kSphere + 40),
                                  PanelLanes::repeated(arrays, 0),
                                  OuterRuleThresholds::far_ratio, lanes) == 0xffu);
  CHECK(lanes.double_layer(3) == Approx(op.entry(kSphere + 43, 0).double_layer).epsilon(1e-13));
  // Panel 0 among the lanes (itself and its neighbours at 0 … 7): not all far.
  CHECK(laplace_far_field_lanes(PanelLanes::repeated(arrays, 0), PanelLanes::consecutive(arrays, 0),
                                OuterRuleThresholds::far_ratio, lanes) != 0xffu);
  // Lanes that need the 7-point rule (first copy) and the 3-point rule (second copy): both
  // computed, each with its own rule.
  const Eigen::Index first = 2 * kSphere - 4;
  REQUIRE(laplace_far_field_lanes(PanelLanes::repeated(arrays, 0), PanelLanes::consecutive(arrays, first),
                                  OuterRuleThresholds::far_ratio, lanes) == 0xffu);
  for (Eigen::Index l = 0; l < kFarFieldLanes; ++l) {
    const auto e = op.entry(0, first + l);
    CHECK(lanes.single_layer(l) == Approx(e.single_layer).epsilon(1e-13));
    CHECK(lanes.double_layer(l) == Approx(e.double_layer).epsilon(1e-13));
  }
}

TEST_CASE("Attenuated Yukawa lanes: fill_row gives entry()'s values") {
  const auto panels = three_spheres();
  const double kappa = 3.0 / panels[0].diameter;  // κ·h = 3, the default element size
  const GalerkinOperators op(YukawaKernel{kappa}, panels);
  const auto n = static_cast<Eigen::Index>(panels.size());
  std::vector<Eigen::Index> columns(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) columns[std::size_t(k)] = k;
  std::vector<GalerkinOperators<YukawaKernel>::Entry> row(columns.size());
  int attenuated = 0;
  for (const Eigen::Index j : {Eigen::Index(0), Eigen::Index(77), kSphere + 5, 2 * kSphere + 300}) {
    op.fill_row(j, columns, row);
    double scale = 0.0;
    for (const auto& e : row) scale = std::max(scale, std::abs(e.single_layer));
    for (Eigen::Index k = 0; k < n; ++k) {
      const Panel& test = panels[std::size_t(j)];
      const Panel& trial = panels[std::size_t(k)];
      attenuated += op.attenuated_points(test, trial, op.separation_ratio(test, trial)) > 0;
      const auto e = op.entry(j, k);
      const auto& f = row[std::size_t(k)];
      REQUIRE(std::abs(f.single_layer - e.single_layer) <= 1e-13 * (std::abs(e.single_layer) + 1e-3 * scale));
      REQUIRE(std::abs(f.double_layer - e.double_layer) <= 1e-13 * (std::abs(e.double_layer) + 1e-3 * scale));
    }
  }
  // Most pairs within a sphere are attenuated at κ·h = 3 (gap > 2.3 h).
  CHECK(attenuated > 600);

  // The lanes alone, against attenuated_entry, with the 4 × 4 rule, for 8 scattered pairs.
  const PanelArrays arrays(panels);
  const std::array<Eigen::Index, kFarFieldLanes> trial{100, 150, 200, 250, 300, 301, 160, 170};
  const TriangleRule& rule = collapsed_gauss_rule(4);
  const FarFieldEntries lanes =
      yukawa_attenuated_lanes(PanelLanes::repeated(arrays, 3), PanelLanes::gathered(arrays, trial), kappa, rule);
  for (int l = 0; l < kFarFieldLanes; ++l) {
    const auto e = op.attenuated_entry(panels[3], panels[std::size_t(trial[std::size_t(l)])], rule);
    CHECK(lanes.single_layer(l) == Approx(e.single_layer).epsilon(1e-13));
    CHECK(lanes.double_layer(l) == Approx(e.double_layer).epsilon(1e-13));
  }
}
