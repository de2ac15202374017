// The surface values of a large sphere against their closed forms, at every vertex:
//
//   build/bench/bench_sphere_surface [FREQUENCY] [--threads N]
//
// Geodesic sphere R = 1 of frequency 64 by default (20·64² = 81,920 faces), h0 = 0.1,
// a = 0.2, the mesh taken as it is (--max-edge just above its longest edge: no remeshing), the
// default solver. s = A·x in the ball, so h_p = h0(1/(h0²A) − a) and h_f = h0(1/(3h0²A) − a)
// on the whole surface (docs/validation.md, "Ball"); the wall measure reads the diameter 2R.
// Prints, per measure, the largest and the RMS relative deviation over the vertices of the
// input mesh (the values a user gets in the output file) and the time.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;

namespace {

struct Deviation {
  double max = 0.0, rms = 0.0;
};

Deviation deviation(const Eigen::VectorXd& values, double exact) {
  const Eigen::ArrayXd relative = (values.array() - exact).abs() / exact;
  return {relative.maxCoeff(), std::sqrt(relative.square().mean())};
}

}  // namespace

int main(int argc, char** argv) {
  int frequency = 64;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--threads" && i + 1 < argc) {
      omp_set_num_threads(std::stoi(argv[++i]));
    } else if (!arg.empty() && arg[0] != '-') {
      frequency = std::stoi(arg);
    } else {
      std::fprintf(stderr, "usage: bench_sphere_surface [FREQUENCY] [--threads N]\n");
      return 2;
    }
  }
  constexpr double kRadius = 1.0;
  const testing::PdeParameters pde{0.1, 0.2};
  const testing::BallSolution ball = testing::ball_solution(pde, kRadius);
  const double h_p = testing::principal_thickness(pde, ball.A);
  const double h_f =
      testing::paper_thickness(pde, testing::inverse_thickness(pde, 3.0 * ball.A));

  const geometry::SurfaceMesh sphere = geometry::make_geodesic_sphere(kRadius, frequency);
  const geometry::PreparedMesh input =
      analysis::prepare_triangles(sphere.vertices(), sphere.faces(), "sphere");
  analysis::ThicknessOptions job;
  job.solve.h0 = pde.h0;
  job.solve.a = pde.a;
  job.solve.max_edge = 1.001 * sphere.max_edge_length();  // the mesh as it is
  job.measure = analysis::ThicknessMeasure::principal;
  const auto start = std::chrono::steady_clock::now();
  const analysis::ThicknessResult result = analysis::measure_thickness(input, job);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const Eigen::MatrixXd& vertex = result.input_features.vertex;
  const Deviation p = deviation(vertex.col(analysis::kColumnHp), h_p);
  const Deviation f = deviation(vertex.col(analysis::kColumnHf), h_f);
  std::printf("sphere R 1, frequency %d: %ld faces (%ld solver faces), h0 %g, a %g, %d threads, "
              "%.1f s\n",
              frequency, long(sphere.num_faces()), long(result.boundary.solver_mesh.num_faces()),
              pde.h0, pde.a, omp_get_max_threads(), seconds);
  std::printf("  sphere (h_p)  exact %.6f  max deviation %.3f %%  rms %.3f %%  over %ld vertices\n",
              h_p, 100.0 * p.max, 100.0 * p.rms, long(vertex.rows()));
  std::printf("  paper (h_f)   exact %.6f  max deviation %.3f %%  rms %.3f %%\n", h_f,
              100.0 * f.max, 100.0 * f.rms);
  return 0;
}
