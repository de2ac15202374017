// Benchmark of the voxel finite-element solver (not a test: it reports, it does not assert).
//
//   bench_fem [N...]        default: 32 64 128 256
//
// For each N: a cubic grid of N³ cells over [−1, 1]³ holding a spherical shell
// (0.3 < r < 0.6) and a plate, h0 = 0.3, a = 0.2; solves all three components of the
// shape-feature PDE with multigrid-preconditioned CG and computes the per-cell features.
// Prints multigrid levels, CG iterations, setup/solve/feature seconds and the peak resident
// memory of the process so far (VmHWM).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/memory.hpp"
#include "fem/characteristic_function.hpp"
#include "fem/shape_feature_solver.hpp"
#include "fem/voxel_features.hpp"

using namespace bemshape;

int main(int argc, char** argv) {
  std::vector<long long> sizes;
  for (int i = 1; i < argc; ++i)
    sizes.push_back(std::atoll(argv[i]));
  if (sizes.empty())
    sizes = {32, 64, 128, 256};
  features::FeatureParameters p;
  p.h0 = 0.3;
  p.a = 0.2;
  std::printf("%6s %10s %7s %6s %9s %9s %9s %9s %10s\n", "N", "cells", "levels", "CG it", "setup s",
              "solve s", "feature s", "total s", "peak MB");
  for (long long n : sizes) {
    fem::VoxelGrid<3> grid;
    grid.cells = {n, n, n};
    grid.cell_size = 2.0 / static_cast<double>(n);
    grid.origin = Eigen::Vector3d::Constant(-1.0);
    const auto start = std::chrono::steady_clock::now();
    fem::fill_characteristic_function<3>(grid, [](const Eigen::Vector3d& x) {
      const double r = x.norm();
      return (r > 0.3 && r < 0.6) ||
             (std::abs(x.z() + 0.75) < 0.1 && std::abs(x.x()) < 0.6 && std::abs(x.y()) < 0.6);
    });
    const auto solution = fem::solve_shape_feature_pde<3>(grid, p);
    const auto before_features = std::chrono::steady_clock::now();
    const auto f = fem::voxel_features<3>(grid, solution.s, p);
    const auto end = std::chrono::steady_clock::now();
    const double feature_s = std::chrono::duration<double>(end - before_features).count();
    const double total_s = std::chrono::duration<double>(end - start).count();
    std::printf("%6lld %10lld %7d %6d %9.2f %9.2f %9.2f %9.2f %10.0f\n", n,
                static_cast<long long>(grid.num_cells()), solution.report.multigrid_levels,
                solution.report.iterations, solution.report.setup_seconds,
                solution.report.solve_seconds, feature_s, total_s,
                static_cast<double>(peak_resident_bytes()) / (1024.0 * 1024.0));
    std::fflush(stdout);
    if (f.field.f_h.size() != grid.num_cells())
      return 1;
  }
  return 0;
}
