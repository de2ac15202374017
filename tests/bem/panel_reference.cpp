#include "tests/bem/panel_reference.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "tests/bem/adaptive_triangle_reference.hpp"

namespace bemshape::testing {
namespace {

constexpr double inv_four_pi = 0.25 / std::numbers::pi;

/// G(r), G'(r), G''(r) of e^{−κr}/(4πr).
struct Radial {
  double g, g1, g2;
};
Radial radial(double kappa, double r) {
  const double e = std::exp(-kappa * r) * inv_four_pi;
  return {e / r, -e * (1 + kappa * r) / (r * r),
          e * (kappa * kappa * r * r + 2 * kappa * r + 2) / (r * r * r)};
}

}  // namespace

NearFieldMagnitudes near_field_magnitudes(const bem::Panel& panel, double kappa) {
  const double h = kappa > 0 ? std::min(panel.diameter, 1.0 / kappa) : panel.diameter;
  const double m = panel.area * inv_four_pi;
  return {m / h, m / (h * h), m / (h * h), m / (h * h * h)};
}

ReferenceIntegrals reference_panel_integrals(double kappa, const bem::Panel& panel,
                                             const Eigen::Vector3d& x, bool with_gradients,
                                             double rel_tol) {
  const NearFieldMagnitudes m = near_field_magnitudes(panel, kappa);
  const double floor_factor = rel_tol * 1e-4;
  const Eigen::Vector3d& n = panel.normal;
  // Plain references, not a structured binding: clang before 16 refuses to capture those.
  const Eigen::Vector3d &a = panel.corners[0], &b = panel.corners[1], &c = panel.corners[2];
  auto integrate = [&](auto&& f, double magnitude) {
    return adaptive_triangle_integral(f, a, b, c, rel_tol, floor_factor * magnitude).value;
  };
  ReferenceIntegrals out;
  out.single_layer = integrate(
      [&](const Eigen::Vector3d& y) { return radial(kappa, (x - y).norm()).g; }, m.single_layer);
  out.double_layer = integrate(
      [&](const Eigen::Vector3d& y) {
        const double r = (x - y).norm();
        return radial(kappa, r).g1 * (y - x).dot(n) / r;
      },
      m.double_layer);
  if (!with_gradients) return out;
  for (int i = 0; i < 3; ++i) {
    out.single_layer_gradient[i] = integrate(
        [&](const Eigen::Vector3d& y) {
          const double r = (x - y).norm();
          return radial(kappa, r).g1 * (x - y)[i] / r;
        },
        m.single_layer_gradient);
    // ∇_x [G'(r)(y − x)·n / r] = −n G'/r + ((y − x)·n) (G''/r − G'/r²)(x − y)/r.
    out.double_layer_gradient[i] = integrate(
        [&](const Eigen::Vector3d& y) {
          const double r = (x - y).norm();
          const Radial k = radial(kappa, r);
          return -n[i] * k.g1 / r + (y - x).dot(n) * (k.g2 / r - k.g1 / (r * r)) * (x - y)[i] / r;
        },
        m.double_layer_gradient);
  }
  return out;
}

std::vector<bem::Panel> rule_test_panels() {
  using Eigen::Vector3d;
  return {bem::make_panel(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0.866, 0)),
          bem::make_panel(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)),
          bem::make_panel(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0.2, 0))};
}

std::vector<Eigen::Vector3d> target_directions(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> dirs = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0),
                                       Eigen::Vector3d(-1, -1, 0.01).normalized()};
  while (static_cast<int>(dirs.size()) < count)
    dirs.push_back(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  return dirs;
}

}  // namespace bemshape::testing
