// The polar scheme against closed forms (flat plane, rectangle solid angle, in-plane Laplace
// single layer) and against the brute-force adaptive reference, for targets on, near and off
// a panel: x' inside, outside, on an edge's line, at a corner; d from 0 to a panel size;
// κ·diameter from 0 to 100.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/polar_quadrature.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "tests/bem/panel_reference.hpp"

using namespace bemshape;
using bem::LaplaceKernel;
using bem::polar_panel_integrals;
using bem::YukawaKernel;
using Eigen::Vector3d;

namespace {

/// Accuracy required of every panel integral (docs/quadrature.md).
constexpr double required_accuracy = 1e-8;
/// Entries below this fraction of the panel's near-field magnitude are compared in absolute
/// terms (they are small by cancellation or by e^{−κ dist}); see panel_reference.hpp.
constexpr double magnitude_floor = 1e-6;

double relative_error(double value, double reference, double magnitude) {
  return std::abs(value - reference) / std::max(std::abs(reference), magnitude_floor * magnitude);
}
double relative_error(const Vector3d& value, const Vector3d& reference, double magnitude) {
  return (value - reference).norm() / std::max(reference.norm(), magnitude_floor * magnitude);
}

/// Two triangles covering the square [−S, S]² in the plane z = 0, normal +z.
std::vector<bem::Panel> square(double S) {
  return {bem::make_panel(Vector3d(-S, -S, 0), Vector3d(S, -S, 0), Vector3d(S, S, 0)),
          bem::make_panel(Vector3d(-S, -S, 0), Vector3d(S, S, 0), Vector3d(-S, S, 0))};
}

template <class Kernel>
bem::PanelIntegrals sum_polar(const Kernel& k, const std::vector<bem::Panel>& panels,
                              const Vector3d& x) {
  bem::PanelIntegrals s;
  for (const auto& p : panels) {
    const auto r = polar_panel_integrals(k, p, x, true);
    s.single_layer += r.single_layer;
    s.double_layer += r.double_layer;
    s.single_layer_gradient += r.single_layer_gradient;
    s.double_layer_gradient += r.double_layer_gradient;
  }
  return s;
}

struct Target {
  std::string name;
  Vector3d in_plane;  // x' (z = 0)
  bool on_boundary;   // x' on an edge line or at a corner: d = 0 is excluded
};

/// The test panel (obtuse-free but not symmetric) and targets around it.
const bem::Panel test_panel =
    bem::make_panel(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.3, 0.8, 0));
const std::vector<Target> targets = {
    {"centroid", test_panel.centroid, false},
    {"inside", Vector3d(0.6, 0.25, 0), false},
    {"inside near edge", Vector3d(0.5, 1e-4, 0), false},
    {"on edge", Vector3d(0.5, 0, 0), true},
    {"on edge line outside", Vector3d(1.4, 0, 0), true},
    {"at corner", Vector3d(1, 0, 0), true},
    {"outside near corner", Vector3d(1 + 1e-4, -1e-4, 0), false},
    {"outside", Vector3d(0.5, -0.3, 0), false},
    {"outside far", Vector3d(2.5, 1.5, 0), false},
};

}  // namespace

TEST_CASE("polar: infinite plane limits for Yukawa (square of side 400/kappa)", "[polar]") {
  for (double kappa : {1.0, 10.0}) {
    const YukawaKernel G(kappa);
    const auto panels = square(200.0 / kappa);
    for (double d : {0.0, 1e-3, 0.01, 0.5, -0.2}) {
      const auto s = sum_polar(G, panels, Vector3d(0.3 / kappa, 0.1 / kappa, d / kappa));
      const double e = std::exp(-std::abs(d));
      INFO("kappa = " << kappa << ", kappa*d = " << d);
      // ∫ Gκ dA = e^{−κ|d|}/(2κ); ∫ ∂G/∂n_y dA = ½ sign(d) e^{−κ|d|}.
      CHECK(s.single_layer == Approx(e / (2 * kappa)).epsilon(1e-13));
      CHECK(s.double_layer == Approx(d == 0 ? 0.0 : std::copysign(0.5 * e, d)).epsilon(1e-13));
      if (d == 0) continue;
      // n·∇ single layer = −½ sign(d)e^{−κ|d|}, n·∇ double layer = −½κ e^{−κ|d|}.
      CHECK(s.single_layer_gradient.z() == Approx(-std::copysign(0.5 * e, d)).epsilon(1e-12));
      CHECK(s.double_layer_gradient.z() == Approx(-0.5 * kappa * e).epsilon(1e-12));
      CHECK(s.single_layer_gradient.head<2>().norm() < 1e-12);
      CHECK(s.double_layer_gradient.head<2>().norm() < 1e-12 * kappa);
    }
  }
}

TEST_CASE("polar: Laplace double layer of a rectangle is its solid angle / 4pi", "[polar]") {
  // Rectangle of half-sides a, b centred below x at height d:
  // Ω = 4 atan(ab / (d √(a² + b² + d²))).
  const double a = 1.0, b = 1.0;
  const auto panels = square(1.0);
  for (double d : {1e-3, 0.05, 0.7, 3.0}) {
    const auto s = sum_polar(LaplaceKernel{}, panels, Vector3d(0, 0, d));
    const double omega = 4.0 * std::atan(a * b / (d * std::sqrt(a * a + b * b + d * d)));
    CHECK(s.double_layer == Approx(omega / (4 * std::numbers::pi)).epsilon(1e-13));
    // Single layer at the centre of a square: closed form of ∫ 1/r over the square, via the
    // z-derivative check n·∇SL = −DL.
    CHECK(s.single_layer_gradient.z() == Approx(-s.double_layer).epsilon(1e-14));
  }
}

TEST_CASE("polar: Laplace single layer in the plane of the panel equals the edge formula",
          "[polar]") {
  // For x in the plane: ∫_T 1/r dA = Σ_edges σ p (asinh(t2/p) − asinh(t1/p)), p the distance
  // from x to the edge's line, t1 < t2 the abscissae of the ends from the foot.
  for (const Target& t : targets) {
    if (t.on_boundary) continue;
    const Vector3d& x = t.in_plane;
    double exact = 0;
    for (int e = 0; e < 3; ++e) {
      const Vector3d a = test_panel.corners[static_cast<size_t>(e)] - x;
      const Vector3d b = test_panel.corners[static_cast<size_t>((e + 1) % 3)] - x;
      const Vector3d u = (b - a).normalized();
      const double h = a.cross(u).dot(test_panel.normal);
      const double p = std::abs(h);
      exact += std::copysign(p, h) * (std::asinh(b.dot(u) / p) - std::asinh(a.dot(u) / p));
    }
    exact /= 4 * std::numbers::pi;
    INFO(t.name);
    CHECK(polar_panel_integrals(LaplaceKernel{}, test_panel, x, false).single_layer ==
          Approx(exact).epsilon(1e-13));
  }
}

TEST_CASE("polar: values match the adaptive reference on, near and off the panel", "[polar]") {
  const std::vector<double> kappa_diameters = {0.0, 0.01, 1.0, 10.0, 100.0};
  const std::vector<double> heights = {0.0, 1e-3, 2e-2, 0.3, -1.0};
  double worst = 0;
  for (double kd : kappa_diameters)
    for (double d : heights)
      for (const Target& t : targets) {
        if (d == 0 && t.on_boundary) continue;
        const Vector3d x = t.in_plane + d * test_panel.normal;
        const double kappa = kd / test_panel.diameter;
        const bem::PanelIntegrals v =
            kd == 0 ? polar_panel_integrals(LaplaceKernel{}, test_panel, x, false)
                    : polar_panel_integrals(YukawaKernel(kappa), test_panel, x, false);
        const auto ref = testing::reference_panel_integrals(kappa, test_panel, x, false);
        const auto m = testing::near_field_magnitudes(test_panel, kappa);
        INFO(t.name << ", kappa*diameter = " << kd << ", d = " << d);
        const double e_sl = relative_error(v.single_layer, ref.single_layer, m.single_layer);
        const double e_dl = relative_error(v.double_layer, ref.double_layer, m.double_layer);
        CHECK(e_sl < required_accuracy);
        CHECK(e_dl < required_accuracy);
        worst = std::max({worst, e_sl, e_dl});
      }
  WARN("polar values: worst relative error " << worst);
}

TEST_CASE("polar: gradients match the adaptive reference near the panel", "[polar][gradient]") {
  double worst = 0;
  for (double kd : {0.0, 1.0, 10.0})
    for (double d : {2e-2, -0.3})
      for (const Target& t : targets) {
        const Vector3d x = t.in_plane + d * test_panel.normal;
        const double kappa = kd / test_panel.diameter;
        const bem::PanelIntegrals v =
            kd == 0 ? polar_panel_integrals(LaplaceKernel{}, test_panel, x, true)
                    : polar_panel_integrals(YukawaKernel(kappa), test_panel, x, true);
        const auto ref = testing::reference_panel_integrals(kappa, test_panel, x, true, 1e-11);
        const auto m = testing::near_field_magnitudes(test_panel, kappa);
        INFO(t.name << ", kappa*diameter = " << kd << ", d = " << d);
        const double e_sl =
            relative_error(v.single_layer_gradient, ref.single_layer_gradient, m.single_layer_gradient);
        const double e_dl =
            relative_error(v.double_layer_gradient, ref.double_layer_gradient, m.double_layer_gradient);
        CHECK(e_sl < required_accuracy);
        CHECK(e_dl < required_accuracy);
        worst = std::max({worst, e_sl, e_dl});
      }
  WARN("polar gradients: worst relative error " << worst);
}

TEST_CASE("polar: gradients at d = 1e-3 panel sizes match finite differences of the values",
          "[polar][gradient]") {
  // Central differences with step δ = 1e-3·|d| have truncation error ~(δ/d)² ≈ 1e−6 and
  // rounding ~1e−16/1e−3: the comparison checks the gradient formulas to ~1e−5.
  constexpr double fd_accuracy = 2e-5;
  for (double kd : {0.0, 1.0, 30.0})
    for (const Target& t : targets) {
      const double d = 1e-3;
      const Vector3d x = t.in_plane + d * test_panel.normal;
      const double kappa = kd / test_panel.diameter;
      auto values = [&](const Vector3d& y, bool grads) {
        return kd == 0 ? polar_panel_integrals(LaplaceKernel{}, test_panel, y, grads)
                       : polar_panel_integrals(YukawaKernel(kappa), test_panel, y, grads);
      };
      const auto v = values(x, true);
      const double step = 1e-3 * d;
      Vector3d fd_sl, fd_dl;
      for (int i = 0; i < 3; ++i) {
        const Vector3d e = Vector3d::Unit(i) * step;
        const auto plus = values(x + e, false), minus = values(x - e, false);
        fd_sl[i] = (plus.single_layer - minus.single_layer) / (2 * step);
        fd_dl[i] = (plus.double_layer - minus.double_layer) / (2 * step);
      }
      const auto m = testing::near_field_magnitudes(test_panel, kappa);
      INFO(t.name << ", kappa*diameter = " << kd);
      CHECK(relative_error(v.single_layer_gradient, fd_sl, m.single_layer_gradient) < fd_accuracy);
      CHECK(relative_error(v.double_layer_gradient, fd_dl, m.double_layer_gradient) < fd_accuracy);
    }
}

TEST_CASE("polar: reflection through the plane", "[polar]") {
  // SL is even in d, DL odd; the normal gradient components flip accordingly.
  const YukawaKernel G(3.0);
  for (const Target& t : targets) {
    const Vector3d up = t.in_plane + 0.05 * test_panel.normal;
    const Vector3d down = t.in_plane - 0.05 * test_panel.normal;
    const auto a = polar_panel_integrals(G, test_panel, up, true);
    const auto b = polar_panel_integrals(G, test_panel, down, true);
    CHECK(a.single_layer == Approx(b.single_layer).epsilon(1e-14));
    CHECK(a.double_layer == Approx(-b.double_layer).epsilon(1e-14));
    CHECK(a.single_layer_gradient.z() == Approx(-b.single_layer_gradient.z()).epsilon(1e-13));
    CHECK(a.double_layer_gradient.z() == Approx(b.double_layer_gradient.z()).epsilon(1e-13));
  }
}

TEST_CASE("polar: the values do not depend on whether gradients are asked for") {
  // The values are summed over arrays of nodes in both cases and the gradients node by node;
  // asking for gradients must leave the single and double layer as they are, for targets
  // inside, outside, on the plane and at a corner, with Laplace and with Yukawa on both sides
  // of the split exponent.
  const bem::Panel panel =
      bem::make_panel(Vector3d(0, 0, 0), Vector3d(1, 0.1, 0), Vector3d(0.3, 0.8, 0.05));
  const Vector3d targets[] = {panel.centroid,
                              panel.centroid + 0.01 * panel.normal,
                              panel.centroid - 0.4 * panel.normal,
                              Vector3d(1.3, 0.9, 0.2),
                              Vector3d(-0.2, -0.1, 0.02),
                              panel.corners[1] + 1e-3 * panel.normal,
                              0.5 * (panel.corners[0] + panel.corners[2]) + 0.05 * panel.normal};
  const auto check = [&](const auto& kernel, const char* name) {
    for (const Vector3d& x : targets) {
      const auto values = polar_panel_integrals(kernel, panel, x, false);
      const auto full = polar_panel_integrals(kernel, panel, x, true);
      INFO(name << " target " << x.transpose());
      CHECK(values.single_layer == Approx(full.single_layer).epsilon(1e-13).margin(1e-300));
      CHECK(std::abs(values.double_layer - full.double_layer) <=
            1e-13 * std::max(std::abs(full.double_layer), std::abs(full.single_layer)));
    }
  };
  check(LaplaceKernel{}, "laplace");
  for (const double kappa : {0.3, 3.0, 30.0}) check(YukawaKernel{kappa}, "yukawa");
}

namespace {

/// Worst error of the Yukawa values at `resolution` against the full resolution, relative to
/// their magnitude bounds over the panel (ρ ≥ c, c the distance from x to T):
///   V: e^{−κc}|T|/(4πc),   K: e^{−κc}(1 + κc)|T|/(4πc²),
/// over targets around the three rule-test panels at distances c up to three diameters,
/// κ·diameter from 3 to 100, in `directions` directions drawn from `seed`.
double worst_attenuated_error(const bem::PolarResolution& resolution, int directions, unsigned seed,
                              double min_attenuation) {
  double worst = 0.0;
  for (const bem::Panel& p : testing::rule_test_panels())
    for (const double kd : {3.0, 10.0, 30.0, 100.0})
      for (const double ratio : {0.0, 0.1, 0.4, 0.8, 1.3, 2.0, 3.0})
        for (const Vector3d& dir : testing::target_directions(directions, seed)) {
          const double kappa = kd / p.diameter;
          const Vector3d x = p.centroid + ratio * p.diameter * dir;
          const double c = bem::distance_to_panel(p, x);
          if (c <= 0.0 || std::exp(-kappa * c) < min_attenuation) continue;
          const YukawaKernel kernel(kappa);
          const auto coarse = polar_panel_integrals(kernel, p, x, false, resolution);
          const auto full = polar_panel_integrals(kernel, p, x, false);
          const double v_bound = std::exp(-kappa * c) * p.area / (4 * std::numbers::pi * c);
          const double k_bound = v_bound * (1.0 + kappa * c) / c;
          worst = std::max({worst, std::abs(coarse.single_layer - full.single_layer) / v_bound,
                            std::abs(coarse.double_layer - full.double_layer) / k_bound});
        }
  return worst;
}

}  // namespace

TEST_CASE("polar resolution: measured errors against the magnitude bound (prints the table)",
          "[.calibration][polar]") {
  // The calibration behind PolarResolution::for_accuracy: the worst error of each number of
  // points per piece and each exponent at which pieces are dropped, relative to the bound
  // e^{−κc}|T|/(4πc) of the single layer (and its double-layer analogue).
  for (const int n : {2, 3, 4, 5, 6, 7, 8, 10})
    for (const double exponent : {3.0, 6.0, 10.0, 15.0, 20.0, 30.0, 45.0}) {
      const double worst = worst_attenuated_error({n, exponent}, 43, 1, 0.0);
      WARN("points per piece " << n << ", dropped beyond e^-" << exponent << ": worst " << worst);
    }
}

TEST_CASE("polar resolution: each accuracy asked is kept, more cheaply than the full one",
          "[polar]") {
  // Targets off the calibration's directions: the values at for_accuracy(τ) are within τ of
  // the magnitude bound, and the coarser accuracies take fewer points than the default.
  for (const double tau : {1e-10, 1e-8, 1e-6, 1e-4, 1e-2, 0.3}) {
    const bem::PolarResolution r = bem::PolarResolution::for_accuracy(tau);
    INFO("accuracy " << tau << ": " << r.points_per_piece << " points per piece, dropped beyond e^-"
                     << r.negligible_exponent);
    CHECK(worst_attenuated_error(r, 9, 17, 0.0) <= tau);
    if (tau >= 1e-6) CHECK(r.points_per_piece < bem::PolarResolution{}.points_per_piece);
  }
  CHECK(bem::PolarResolution::for_accuracy(1e-12).points_per_piece ==
        bem::PolarResolution{}.points_per_piece);
}
