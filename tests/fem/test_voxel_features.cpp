// Features of voxel solutions against the paper and the closed forms:
//  - the paper's "multiple bars" image (section "Numerical validation in two dimensions"):
//    1/f_h is linear in the bar thickness h with slope 1/h0 and intercept a (from the 1-D
//    solution: 1/f_h = a(κh + 2)/2 = h/h0 + a), and h_f equals h for bars at least h0 thick;
//  - a ball, a spherical shell and a plate (tests/support/closed_forms.hpp), χ from analytic
//    inside tests, f_h within 2% at interior probes;
//  - a ball voxelised from a surface mesh through geometry's exact inside test.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>

#include "fem/binary_image.hpp"
#include "fem/characteristic_function.hpp"
#include "fem/shape_feature_solver.hpp"
#include "fem/voxel_features.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
using namespace bemshape::fem;
namespace ref = bemshape::testing;

namespace {

/// Relative error allowed for f_h at interior probes: at κ·cell = 0.5 the Q1 solution's
/// exterior boundary layer and the staircase surface together give about 1–1.5%
/// (docs/validation.md, convergence tables), so 2% separates that from a real defect.
constexpr double kProbeTolerance = 0.02;

/// Bar thicknesses of the paper's example [model units].
constexpr std::array<double, 8> kBarThickness{0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.55, 0.6};

/// The paper's 8 × 5 image: vertical bars y ∈ [0.5, 4.5), bar i from x = i + 1/4, thickness
/// kBarThickness[i]; gaps ≥ 0.4 ≫ 1/κ = 0.03, so the bars do not see each other.
BinaryImage<2> multiple_bars_image(double pixel) {
  const auto pixels = [pixel](double length) {
    return static_cast<GridIndex>(std::lround(length / pixel));
  };
  BinaryImage<2> image;
  image.size = {pixels(8.0), pixels(5.0)};
  image.solid.assign(static_cast<std::size_t>(image.num_pixels()), 0);
  for (std::size_t i = 0; i < kBarThickness.size(); ++i) {
    const GridIndex x0 = pixels(static_cast<double>(i) + 0.25), x1 = x0 + pixels(kBarThickness[i]);
    for (GridIndex y = pixels(0.5); y < pixels(4.5); ++y)
      for (GridIndex x = x0; x < x1; ++x)
        image.solid[static_cast<std::size_t>(y * image.size[0] + x)] = 1;
  }
  return image;
}

template <int D>
double f_h_at(const VoxelGrid<D>& grid, const VoxelFeatures<D>& features,
              const Eigen::Matrix<double, D, 1>& x) {
  std::array<GridIndex, D> c{};
  for (int d = 0; d < D; ++d)
    c[d] = static_cast<GridIndex>(std::floor((x(d) - grid.origin(d)) / grid.cell_size));
  return features.field.f_h[grid.cell_index(c)];
}

VoxelFeatures<3> solve_3d(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell,
                          const features::FeatureParameters& p, const InsideTest<3>& inside) {
  auto grid = grid_around<3>(lo, hi, cell, p, kDefaultMaxCells<3>);
  fill_characteristic_function<3>(grid, inside);
  const auto solution = solve_shape_feature_pde<3>(grid, p);
  return voxel_features<3>(grid, solution.s, p);
}

}  // namespace

TEST_CASE("multiple bars: 1/f_h linear in thickness with slope 1/h0 and intercept a") {
  // Pixel = cell = 0.005 (κ·cell = 0.17): the intercept a is the small difference of
  // 1/f_h ≈ 1–2.2 and h/h0, so it needs 1/f_h to about 0.1%; at 0.01 it is 3% off.
  constexpr double kPixel = 0.005;
  features::FeatureParameters p;
  p.h0 = 0.3;
  p.a = 0.2;
  // Round trip through a PNG file: the solver sees what a user's image would give.
  const auto path = std::filesystem::temp_directory_path() / "bemshape_test_multiple_bars.png";
  write_binary_png(path, multiple_bars_image(kPixel));
  const BinaryImage<2> image = read_png_image(path);
  std::filesystem::remove(path);
  REQUIRE(image.solid == multiple_bars_image(kPixel).solid);

  const auto grid = grid_for_image<2>(image, kPixel, kPixel, p);
  const auto solution = solve_shape_feature_pde<2>(grid, p);
  const auto features = voxel_features<2>(grid, solution.s, p);

  // Mean 1/f_h and h_f over the central part of each bar, y ∈ [2.25, 2.75]: inside a bar s
  // is harmonic, so the ends' influence decays like e^{−π·d/h}, below 1e−4 at d = 1.75 for
  // the thickest bar (over y ∈ [1.5, 3.5] the 0.6 bar would read 0.3% thin, enough to move
  // the fitted intercept by 3%).
  std::array<double, 8> inverse{}, thickness{};
  std::array<int, 8> count{};
  for (GridIndex e = 0; e < grid.num_cells(); ++e) {
    if (grid.chi[e] < kSolidFraction)
      continue;
    const Eigen::Vector2d x = grid.cell_centre(grid.cell_multi_index(e));
    if (x.y() < 2.25 || x.y() > 2.75)
      continue;
    const auto bar = static_cast<std::size_t>(std::floor(x.x()));
    inverse[bar] += 1.0 / features.field.f_h[e];
    thickness[bar] += features.field.h_f[e];
    ++count[bar];
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  const double n = kBarThickness.size();
  for (std::size_t i = 0; i < kBarThickness.size(); ++i) {
    REQUIRE(count[i] > 0);
    inverse[i] /= count[i];
    thickness[i] /= count[i];
    const double h = kBarThickness[i];
    sx += h;
    sy += inverse[i];
    sxx += h * h;
    sxy += h * inverse[i];
    syy += inverse[i] * inverse[i];
    INFO("bar " << h << ": mean 1/f_h " << inverse[i] << " (1-D: " << h / p.h0 + p.a
                << "), mean h_f " << thickness[i]);
    if (h >= p.h0)
      CHECK(thickness[i] == Approx(h).epsilon(0.02));
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  const double r = (n * sxy - sx * sy) / std::sqrt((n * sxx - sx * sx) * (n * syy - sy * sy));
  INFO(std::setprecision(8) << "slope " << slope << " intercept " << intercept << " R² " << r * r
                            << " mean 1/f_h of the bars 0.2, 0.25: " << inverse[0] << ", "
                            << inverse[1]);
  CHECK(r * r >= 0.9999);
  CHECK(slope == Approx(1.0 / p.h0).epsilon(0.02));
  CHECK(intercept == Approx(p.a).epsilon(0.02));
  // Multigrid keeps the iteration count small on this 2-D grid of ~10⁶ cells.
  CHECK(solution.report.iterations <= 20);
}

TEST_CASE("ball: f_h within 2% of the closed form at interior probes") {
  // R = 0.5, h0 = 0.3: f_h = 0.801142 inside the whole ball. Cell 0.015 = 0.5/κ.
  features::FeatureParameters p;
  p.h0 = 0.3;
  const double R = 0.5;
  const double expected =
      ref::inverse_thickness({0.3, 0.2}, 3.0 * ref::ball_solution({0.3, 0.2}, R).A);
  REQUIRE(expected == Approx(0.801142).epsilon(1e-5));
  const auto features = solve_3d(Eigen::Vector3d::Constant(-R), Eigen::Vector3d::Constant(R), 0.015,
                                 p, [R](const Eigen::Vector3d& x) { return x.norm() < R; });
  auto grid = grid_around<3>(Eigen::Vector3d::Constant(-R), Eigen::Vector3d::Constant(R), 0.015, p,
                             kDefaultMaxCells<3>);
  for (const Eigen::Vector3d& probe :
       {Eigen::Vector3d(0.01, 0.01, 0.01), Eigen::Vector3d(0.2, 0.0, 0.0),
        Eigen::Vector3d(0.0, -0.2, 0.1), Eigen::Vector3d(0.1, 0.1, -0.2)}) {
    INFO("probe " << probe.transpose());
    CHECK(f_h_at<3>(grid, features, probe) == Approx(expected).epsilon(kProbeTolerance));
  }
}

TEST_CASE("spherical shell: f_h within 2% of the closed form at mid-wall probes") {
  // R1 = 0.7, R2 = 1.0 with h0 = 0.5 (κ = 20) and cell 0.025 = 0.5/κ, the same resolution
  // relative to the boundary layer as the ball test at a quarter of the cells.
  features::FeatureParameters p;
  p.h0 = 0.5;
  const ref::PdeParameters rp{0.5, 0.2};
  const double expected = ref::inverse_thickness(rp, 3.0 * ref::shell_solution(rp, 0.7, 1.0).A);
  const auto inside = [](const Eigen::Vector3d& x) { return x.norm() > 0.7 && x.norm() < 1.0; };
  const auto features =
      solve_3d(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0), 0.025, p, inside);
  auto grid = grid_around<3>(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0), 0.025,
                             p, kDefaultMaxCells<3>);
  for (const Eigen::Vector3d& direction :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, 1, 1).normalized(),
        Eigen::Vector3d(-1, 2, 0.5).normalized()}) {
    const Eigen::Vector3d probe = 0.85 * direction;
    INFO("probe " << probe.transpose());
    CHECK(f_h_at<3>(grid, features, probe) == Approx(expected).epsilon(kProbeTolerance));
  }
}

TEST_CASE("plate: f_h and h_f match the 1-D closed form in the plate's interior") {
  // Plate 1.4 × 1.4 × 0.3 (h0 = 0.3), cell 0.015 (faces on grid lines): probes ≥ 0.5 from
  // the plate's rim, where the rim's influence has decayed like e^{−π·0.5/0.3} < 1%.
  features::FeatureParameters p;
  p.h0 = 0.3;
  const double t = 0.3;
  const double expected = ref::inverse_thickness({0.3, 0.2}, ref::plate_slope({0.3, 0.2}, t));
  const Eigen::Vector3d lo(-0.7, -0.7, -0.5 * t), hi(0.7, 0.7, 0.5 * t);
  const auto inside = [&](const Eigen::Vector3d& x) {
    return (x.array() > lo.array()).all() && (x.array() < hi.array()).all();
  };
  const auto features = solve_3d(lo, hi, 0.015, p, inside);
  auto grid = grid_around<3>(lo, hi, 0.015, p, kDefaultMaxCells<3>);
  for (const Eigen::Vector3d& probe :
       {Eigen::Vector3d(0.0, 0.0, 0.01), Eigen::Vector3d(0.2, -0.1, 0.1),
        Eigen::Vector3d(-0.15, 0.2, -0.1)}) {
    INFO("probe " << probe.transpose());
    CHECK(f_h_at<3>(grid, features, probe) == Approx(expected).epsilon(kProbeTolerance));
  }
}

TEST_CASE("ball voxelised from a surface mesh agrees with the analytic indicator") {
  // geometry's exact inside test on a geodesic sphere: χ differs from the analytic ball only
  // in cells cut by the chordal error of the triangulation, so f_h agrees to well below the
  // discretisation error.
  features::FeatureParameters p;
  p.h0 = 0.5;
  const double R = 0.5, cell = 0.05;
  const auto mesh = geometry::make_geodesic_sphere(R, 24);
  auto from_mesh = grid_for_mesh(mesh, cell, p);
  auto analytic = from_mesh;
  fill_characteristic_function<3>(analytic, [R](const Eigen::Vector3d& x) { return x.norm() < R; });
  GridIndex differ = 0, solid = 0;
  for (std::size_t e = 0; e < analytic.chi.size(); ++e) {
    differ += analytic.chi[e] != from_mesh.chi[e];
    solid += analytic.chi[e] > 0.5f;
  }
  CHECK(differ <= solid / 100);
  const auto a = voxel_features<3>(analytic, solve_shape_feature_pde<3>(analytic, p).s, p);
  const auto b = voxel_features<3>(from_mesh, solve_shape_feature_pde<3>(from_mesh, p).s, p);
  const Eigen::Vector3d centre(0.01, 0.01, 0.01);
  CHECK(f_h_at<3>(from_mesh, b, centre) == Approx(f_h_at<3>(analytic, a, centre)).epsilon(0.005));
}
