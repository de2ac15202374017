// Throughput of the panel integrals in a dense far-field loop: every (centroid, panel) pair of
// a geodesic sphere whose distance ratio puts it in the Gauss range, as the dense assembly and
// the ACA row/column generators will call them, and the far-field lanes those generators use
// (V and K of 8 pairs at once, bem/operators/far_field_lanes.hpp); then the cost per point of the larger
// Gauss rules (gauss_panel_integrals) on one panel and of the exponential per SIMD lane
// (linalg/vector_exponential.hpp against Eigen's), and the cost of one call of the Yukawa polar
// scheme (bem/quadrature/polar_quadrature.hpp) at the resolutions the exterior near field asks
// for. Not a test: prints entries per second and nanoseconds.
//
//   build/bench/bench_panel_integrals [frequency=24]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bem/operators/far_field_lanes.hpp"
#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/operators/panel_arrays.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/quadrature/polar_quadrature.hpp"
#include "linalg/vector_exponential.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/surface_mesh.hpp"

namespace {

using namespace bemshape;
using Clock = std::chrono::steady_clock;

/// One line of the throughput table.
void print_throughput(const char* name, long count, double seconds, double checksum) {
  std::printf("%-34s %10ld entries  %7.3f s  %8.2e entries/s  (checksum %.12g)\n", name, count,
              seconds, count / seconds, checksum);
}

template <class F>
void measure(const char* name, const std::vector<bem::Panel>& panels, F&& entry) {
  const auto n = panels.size();
  double checksum = 0.0;
  long count = 0;
  const auto start = Clock::now();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& x = panels[i].centroid;
    for (size_t k = 0; k < n; ++k) {
      if (k == i)
        continue;
      checksum += entry(panels[k], x);
      ++count;
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  print_throughput(name, count, seconds, checksum);
}

/// Entries per second of the assembly's own far-field path, laplace_far_field_lanes: each
/// centroid against consecutive panels 8 at a time, V and K together, the pairs it computes
/// (those at least OuterRuleThresholds::far_ratio diameters apart) counted.
void measure_far_field_lanes(const std::vector<bem::Panel>& panels) {
  const bem::PanelArrays arrays(panels);
  const auto n = static_cast<Eigen::Index>(panels.size());
  double checksum = 0.0;
  long count = 0;
  bem::FarFieldEntries e{bem::FarFieldLanes::Zero(), bem::FarFieldLanes::Zero()};
  const auto start = Clock::now();
  for (Eigen::Index i = 0; i < n; ++i) {
    const bem::PanelLanes test = bem::PanelLanes::repeated(arrays, i);
    for (Eigen::Index k = 0; k + bem::kFarFieldLanes <= n; k += bem::kFarFieldLanes) {
      const unsigned done = bem::laplace_far_field_lanes(
          test, bem::PanelLanes::consecutive(arrays, k), bem::OuterRuleThresholds::far_ratio, e);
      for (int l = 0; l < bem::kFarFieldLanes; ++l)
        if (done & (1u << l)) {
          checksum += e.single_layer(l) + e.double_layer(l);
          ++count;
        }
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  print_throughput("Laplace far-field lanes (V and K)", count, seconds, checksum);
}

/// The panel measure_rule integrates over: a scalene triangle, slightly tilted.
bem::Panel rule_panel() {
  return bem::make_panel(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                         Eigen::Vector3d(0.4, 0.9, 0.1));
}

/// Nanoseconds per rule point of gauss_panel_integrals by `rule` over 1000 targets at 2 to 4
/// diameters from rule_panel(), repeated.
template <class Kernel>
void measure_rule(const char* name, const Kernel& kernel, const bem::TriangleRule& rule) {
  const bem::Panel panel = rule_panel();
  std::vector<Eigen::Vector3d> targets;
  for (int i = 0; i < 1000; ++i) {
    const double t = 0.001 * i;
    const Eigen::Vector3d direction(std::cos(17.0 * t), std::sin(17.0 * t), 2.0 * t - 1.0);
    targets.push_back(panel.centroid + (2.0 + 2.0 * t) * panel.diameter * direction.normalized());
  }
  constexpr int repeats = 2000;
  double checksum = 0.0;
  const auto start = Clock::now();
  for (int r = 0; r < repeats; ++r)
    for (const Eigen::Vector3d& x : targets) {
      const bem::PanelIntegrals p = bem::gauss_panel_integrals(kernel, panel, x, rule, false);
      checksum += p.single_layer + p.double_layer;
    }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("%-34s %2d points  %6.2f ns per point  (checksum %.12g)\n", name, rule.size(),
              1e9 * seconds / (double(repeats) * double(targets.size()) * rule.size()), checksum);
}

/// Microseconds per call of the Yukawa polar scheme, values only, on a panel 11/κ across
/// (12 × 10, κ = 0.875: a wall-reading element of plate_holes) for 4,000 targets spread over
/// the panel and up to 6 beside it and 8 above or below it, at the resolution for `accuracy`.
void measure_polar(double accuracy) {
  Eigen::MatrixX3d vertices(3, 3);
  vertices << 0, 0, 0, 12, 0, 0, 4, 10, 0;
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 2;
  const bem::Panel panel = bem::make_panels(geometry::SurfaceMesh(vertices, faces))[0];
  const bem::YukawaKernel kernel{0.875};
  const bem::PolarResolution resolution = bem::PolarResolution::for_accuracy(accuracy);
  std::vector<Eigen::Vector3d> targets;
  for (int i = 0; i < 4000; ++i) {
    // A deterministic scatter (golden-ratio sequences) over [−6, 18] × [−4.8, 14.4] × [0.2, 8].
    const double a = std::fmod(0.6180339887 * i, 1.0), b = std::fmod(0.7548776662 * i, 1.0);
    const double c = std::fmod(0.5698402910 * i, 1.0);
    targets.emplace_back(-6.0 + 24.0 * a, 0.8 * (-6.0 + 24.0 * b), (i % 2 ? 1 : -1) * (0.2 + 7.8 * c));
  }
  constexpr int repeats = 50;
  double checksum = 0.0;
  const auto start = Clock::now();
  for (int r = 0; r < repeats; ++r)
    for (const Eigen::Vector3d& x : targets)
      checksum += bem::polar_panel_integrals(kernel, panel, x, false, resolution).single_layer;
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("Yukawa polar scheme, accuracy %-7.0e %2d points per piece  %6.3f us per call  (checksum %.12g)\n",
              accuracy, resolution.points_per_piece,
              1e6 * seconds / (double(repeats) * double(targets.size())), checksum);
}

/// Nanoseconds per entry of e^x over arrays of 64 arguments in [−30, 0].
template <class Exponential>
void measure_exponential(const char* name, Exponential&& exponential) {
  using Chunk = Eigen::Array<double, 64, 1>;
  const Chunk x = Chunk::LinSpaced(-30.0, -1e-3);
  constexpr int repeats = 400000;
  Chunk sum = Chunk::Zero();
  const auto start = Clock::now();
  for (int r = 0; r < repeats; ++r)
    sum += exponential(Chunk(x - 1e-12 * r));
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("%-34s %6.2f ns per entry  (checksum %.12g)\n", name,
              1e9 * seconds / (double(repeats) * double(x.size())), sum.sum());
}

}  // namespace

int main(int argc, char** argv) {
  const int frequency = argc > 1 ? std::atoi(argv[1]) : 24;
  const auto mesh = geometry::make_geodesic_sphere(1.0, frequency);
  const std::vector<bem::Panel> panels = bem::make_panels(mesh);
  std::printf("geodesic sphere, frequency %d: %zu panels, diameter %.4f\n", frequency,
              panels.size(), panels[0].diameter);
  const bem::LaplaceKernel laplace{};
  const double h0 = 4.0 * panels[0].diameter;  // panels ≈ h0/4
  const bem::YukawaKernel yukawa{2.0 / (0.2 * h0)};
  measure("Laplace single_layer()", panels, [&](const bem::Panel& p, const Eigen::Vector3d& x) {
    return bem::single_layer(laplace, p, x);
  });
  measure("Laplace integrate_panel (SL+DL)", panels,
          [&](const bem::Panel& p, const Eigen::Vector3d& x) {
            const auto r = bem::integrate_panel(laplace, p, x);
            return r.single_layer + r.double_layer;
          });
  measure("Yukawa integrate_panel (SL+DL)", panels,
          [&](const bem::Panel& p, const Eigen::Vector3d& x) {
            const auto r = bem::integrate_panel(yukawa, p, x);
            return r.single_layer + r.double_layer;
          });
  measure_far_field_lanes(panels);
  // κ·diameter = 3, the default element size's (bem/kernels/transmission_parameters.hpp).
  const bem::YukawaKernel yukawa_unit{3.0 / rule_panel().diameter};
  for (const int n : {4, 6, 8}) {
    measure_rule("Laplace Gauss rule, one panel", laplace, bem::collapsed_gauss_rule(n));
    measure_rule("Yukawa Gauss rule, one panel", yukawa_unit, bem::collapsed_gauss_rule(n));
  }
  measure_exponential("e^x, linalg::vector_exp", [](const auto& x) {
    return linalg::vector_exp<Eigen::Array<double, 64, 1>>(x);
  });
  measure_exponential("e^x, Eigen exp",
                      [](const auto& x) { return Eigen::Array<double, 64, 1>(x.exp()); });
  for (const double accuracy : {1e-10, 1e-7, 1e-5, 1e-3}) measure_polar(accuracy);
  return 0;
}
