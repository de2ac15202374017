// Throughput of the panel integrals in a dense far-field loop: every (centroid, panel) pair of
// a geodesic sphere whose distance ratio puts it in the Gauss range, as the dense assembly and
// the ACA row/column generators will call them. Not a test: prints entries per second.
//
//   build-bem/bench/bench_panel_integrals [frequency=24]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bem/laplace_kernel.hpp"
#include "bem/panel.hpp"
#include "bem/panel_integrals.hpp"
#include "bem/yukawa_kernel.hpp"
#include "geometry/primitive_meshes.hpp"

namespace {

using namespace bemshape;
using Clock = std::chrono::steady_clock;

template <class F>
void measure(const char* name, const std::vector<bem::Panel>& panels, F&& entry) {
  const auto n = panels.size();
  double checksum = 0.0;
  long count = 0;
  const auto start = Clock::now();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& x = panels[i].centroid;
    for (size_t k = 0; k < n; ++k) {
      if (k == i) continue;
      checksum += entry(panels[k], x);
      ++count;
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("%-34s %10ld entries  %7.3f s  %8.2e entries/s  (checksum %.12g)\n", name, count,
              seconds, count / seconds, checksum);
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
  return 0;
}
