// Convergence tables of the voxel FEM against the closed forms, for docs/validation.md
// (section "Voxel FEM"); the assertions live in tests/fem/, this program only reports.
//
//   fem_validation bars FOLDER   writes FOLDER/multiple_bars.png, the paper's 8 × 5 bars
//                                image at 200 pixels per unit (pixel 0.005)
//   fem_validation 1d            2-D straight bar vs the paper's 1-D solution (finite K, L)
//   fem_validation ball|shell|plate [CELL...]   f_h at interior probes vs the closed form
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fem/binary_image.hpp"
#include "fem/characteristic_function.hpp"
#include "fem/shape_feature_solver.hpp"
#include "fem/voxel_features.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
namespace ref = bemshape::testing;

namespace {

constexpr double kBarThickness[] = {0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.55, 0.6};

void write_bars(const std::string& folder) {
  const double pixel = 0.005;
  const auto pixels = [pixel](double length) {
    return static_cast<long long>(std::lround(length / pixel));
  };
  fem::BinaryImage<2> image;
  image.size = {pixels(8.0), pixels(5.0)};
  image.solid.assign(static_cast<std::size_t>(image.num_pixels()), 0);
  for (int i = 0; i < 8; ++i) {
    const long long x0 = pixels(i + 0.25), x1 = x0 + pixels(kBarThickness[i]);
    for (long long y = pixels(0.5); y < pixels(4.5); ++y)
      for (long long x = x0; x < x1; ++x)
        image.solid[static_cast<std::size_t>(y * image.size[0] + x)] = 1;
  }
  fem::write_binary_png(folder + "/multiple_bars.png", image);
  std::printf("wrote %s/multiple_bars.png (%lld x %lld pixels, pixel 0.005)\n", folder.c_str(),
              static_cast<long long>(image.size[0]), static_cast<long long>(image.size[1]));
}

void one_dimensional() {
  features::FeatureParameters p;
  p.h0 = 0.2;
  p.a = 0.2;
  const auto exact = ref::interval_1d_solution({0.2, 0.2}, 0.0, 1.0, 0.4, 0.2);
  std::printf(
      "| cell | kappa*cell | max abs(s_h - s) / max abs(s) | h_f at bar centre (exact 0.2) | CG it "
      "|\n|---|---|---|---|---|\n");
  for (long long n : {40, 80, 160, 320, 640}) {
    fem::VoxelGrid<2> grid;
    grid.cells = {n, n};
    grid.cell_size = 1.0 / static_cast<double>(n);
    fem::fill_characteristic_function<2>(
        grid, [](const Eigen::Vector2d& x) { return x.x() > 0.4 && x.x() < 0.6; });
    const auto solution = fem::solve_shape_feature_pde<2>(grid, p);
    double error = 0.0, size = 0.0;
    for (long long i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) / static_cast<double>(n);
      error = std::max(error, std::abs(solution.s(grid.node_index({i, n / 2}), 0) - exact.s(x)));
      size = std::max(size, std::abs(exact.s(x)));
    }
    const auto f = fem::voxel_features<2>(grid, solution.s, p);
    std::printf("| 1/%lld | %.3f | %.2e | %.5f | %d |\n", n, p.kappa() / static_cast<double>(n),
                error / size, f.field.h_f[grid.cell_index({n / 2, n / 2})],
                solution.report.iterations);
  }
}

void solid(const std::string& kind, std::vector<double> cells) {
  features::FeatureParameters p;
  p.h0 = 0.3;
  p.a = 0.2;
  const ref::PdeParameters rp{0.3, 0.2};
  Eigen::Vector3d lo, hi;
  fem::InsideTest<3> inside;
  double expected = 0.0;
  std::vector<Eigen::Vector3d> probes;
  if (kind == "ball") {
    lo = Eigen::Vector3d::Constant(-0.5);
    hi = -lo;
    inside = [](const Eigen::Vector3d& x) { return x.norm() < 0.5; };
    expected = ref::inverse_thickness(rp, 3.0 * ref::ball_solution(rp, 0.5).A);
    probes = {{0.01, 0.01, 0.01}, {0.2, 0.0, 0.0}, {0.0, -0.2, 0.1}, {0.1, 0.1, -0.2}};
  } else if (kind == "shell") {
    lo = Eigen::Vector3d::Constant(-1.0);
    hi = -lo;
    inside = [](const Eigen::Vector3d& x) { return x.norm() > 0.7 && x.norm() < 1.0; };
    expected = ref::inverse_thickness(rp, 3.0 * ref::shell_solution(rp, 0.7, 1.0).A);
    for (Eigen::Vector3d d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0),
                              Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(-1, 2, 0.5)})
      probes.push_back(0.85 * d.normalized());
  } else {
    lo = Eigen::Vector3d(-0.7, -0.7, -0.15);
    hi = -lo;
    inside = [lo, hi](const Eigen::Vector3d& x) {
      return (x.array() > lo.array()).all() && (x.array() < hi.array()).all();
    };
    expected = ref::inverse_thickness(rp, ref::plate_slope(rp, 0.3));
    probes = {{0.0, 0.0, 0.01}, {0.2, -0.1, 0.1}, {-0.15, 0.2, -0.1}};
  }
  if (cells.empty())
    cells = {0.04, 0.03, 0.02, 0.015};
  std::printf(
      "%s: exact f_h = %.6f\n| cell | kappa*cell | grid | max rel. error of f_h at %zu probes | CG "
      "it |\n|---|---|---|---|---|\n",
      kind.c_str(), expected, probes.size());
  for (double cell : cells) {
    auto grid = fem::grid_around<3>(lo, hi, cell, p, 20'000'000);
    fem::fill_characteristic_function<3>(grid, inside);
    const auto solution = fem::solve_shape_feature_pde<3>(grid, p);
    const auto f = fem::voxel_features<3>(grid, solution.s, p);
    double worst = 0.0;
    std::string signed_errors;
    for (const auto& x : probes) {
      std::array<fem::GridIndex, 3> c{};
      for (int d = 0; d < 3; ++d)
        c[d] = static_cast<fem::GridIndex>(std::floor((x(d) - grid.origin(d)) / cell));
      const double error = f.field.f_h[grid.cell_index(c)] / expected - 1.0;
      worst = std::max(worst, std::abs(error));
      char text[32];
      std::snprintf(text, sizeof text, "%s%+.2f%%", signed_errors.empty() ? "" : ", ",
                    100.0 * error);
      signed_errors += text;
    }
    std::printf("| %.3f | %.2f | %lld x %lld x %lld | %.2f%% (%s) | %d |\n", cell, p.kappa() * cell,
                static_cast<long long>(grid.cells[0]), static_cast<long long>(grid.cells[1]),
                static_cast<long long>(grid.cells[2]), 100.0 * worst, signed_errors.c_str(),
                solution.report.iterations);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fem_validation bars FOLDER | 1d | ball|shell|plate [CELL...]\n");
    return 2;
  }
  const std::string what = argv[1];
  if (what == "bars" && argc == 3) {
    write_bars(argv[2]);
  } else if (what == "1d") {
    one_dimensional();
  } else {
    std::vector<double> cells;
    for (int i = 2; i < argc; ++i)
      cells.push_back(std::atof(argv[i]));
    solid(what, cells);
  }
  return 0;
}
