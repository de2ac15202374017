// BEM accuracy against the closed forms, printed as the Markdown tables of
// docs/validation.md:  build/bench/bem_validation [ball|shell|plate|all]
//
// Ball R = 0.5, shell R1 = 0.7 / R2 = 1.0 and a 4 × 4 × 0.3 plate, h0 = 0.3, a = 0.2, dense
// P0 Galerkin path. Errors are maxima of |f_h − exact|/exact: at 20 random interior points
// (fixed seed; |x| < 0.9R for the ball), at the centre of the ball, and on every face
// (surface gradient ∇_Γφ + q n).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "bem/solve/dense_transmission_solver.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "bem/evaluate/surface_gradient.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
namespace ref = bemshape::testing;

namespace {
const ref::PdeParameters kPaper{0.3, 0.2};
const auto kParameters = bem::TransmissionParameters::from_shape(kPaper.h0, kPaper.a);

double trace(const Eigen::MatrixXd& g, Eigen::Index r) { return g(r, 0) + g(r, 4) + g(r, 8); }

Eigen::MatrixX3d random_points(int n, double r_min, double r_max, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-r_max, r_max);
  Eigen::MatrixX3d p(n, 3);
  for (int c = 0; c < n;) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    if (x.norm() > r_min && x.norm() < r_max) p.row(c++) = x.transpose();
  }
  return p;
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void ball() {
  const double radius = 0.5;
  const double exact = ref::inverse_thickness(kPaper, 3.0 * ref::ball_solution(kPaper, radius).A);
  std::printf("| frequency | faces | longest edge | κ·h | f_h at centre | f_h interior (max, 20 pts) | f_h surface (max) | time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (int n : {4, 6, 8, 12}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto mesh = geometry::make_geodesic_sphere(radius, n);
    const auto sol = bem::solve_transmission_dense(mesh, kParameters);
    const auto g = bem::interior_surface_gradient(mesh, sol);
    double surface = 0.0;
    for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
      surface = std::max(surface, std::abs(kPaper.h0 * kPaper.h0 * trace(g.face_gradient, f) - exact) / exact);
    Eigen::MatrixX3d points(21, 3);
    points.topRows(20) = random_points(20, 0.0, 0.9 * radius, 7);
    points.row(20).setZero();
    const auto field = bem::evaluate_potential(mesh, sol, points);
    double interior = 0.0;
    for (Eigen::Index p = 0; p < 20; ++p)
      interior = std::max(interior, std::abs(kPaper.h0 * kPaper.h0 * trace(field.gradient, p) - exact) / exact);
    const double centre = std::abs(kPaper.h0 * kPaper.h0 * trace(field.gradient, 20) - exact) / exact;
    std::printf("| %d | %ld | %.4f | %.2f | %.2e | %.2e | %.2e | %.1f |\n", n, long(mesh.num_faces()),
                mesh.max_edge_length(), kParameters.kappa * mesh.max_edge_length(), centre, interior,
                surface, seconds(t0));
    std::fflush(stdout);
  }
}

void shell() {
  const double r1 = 0.7, r2 = 1.0, edge = kParameters.default_max_edge();
  const auto t0 = std::chrono::steady_clock::now();
  const auto mesh = geometry::make_spherical_shell(r1, r2, geometry::geodesic_frequency_for_edge(r1, edge),
                                                   geometry::geodesic_frequency_for_edge(r2, edge));
  const double exact = ref::inverse_thickness(kPaper, 3.0 * ref::shell_solution(kPaper, r1, r2).A);
  const auto sol = bem::solve_transmission_dense(mesh, kParameters);
  const auto g = bem::interior_surface_gradient(mesh, sol);
  double inner = 0.0, outer = 0.0;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    const double e = std::abs(kPaper.h0 * kPaper.h0 * trace(g.face_gradient, f) - exact) / exact;
    double& side = mesh.face_centroids().row(f).norm() < 0.85 ? inner : outer;
    side = std::max(side, e);
  }
  const auto field = bem::evaluate_potential(mesh, sol, random_points(20, r1, r2, 11));
  double interior = 0.0;
  for (Eigen::Index p = 0; p < 20; ++p)
    interior = std::max(interior, std::abs(kPaper.h0 * kPaper.h0 * trace(field.gradient, p) - exact) / exact);
  std::printf("| faces | longest edge | f_h interior (max, 20 pts) | inner surface | outer surface | time [s] |\n|---|---|---|---|---|---|\n");
  std::printf("| %ld | %.4f | %.2e | %.2e | %.2e | %.1f |\n", long(mesh.num_faces()), mesh.max_edge_length(),
              interior, inner, outer, seconds(t0));
}

void plate() {
  const double t = 0.3;
  std::printf("| edge | κ·h | faces | thickness, middle faces (max rel. error) | thickness at 3 interior points (max rel. error) | time [s] |\n|---|---|---|---|---|---|\n");
  for (double edge : {0.3, 0.15}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto mesh = geometry::make_box(Eigen::Vector3d(-2, -2, -t / 2), Eigen::Vector3d(2, 2, t / 2), edge);
    const auto sol = bem::solve_transmission_dense(mesh, kParameters);
    const auto g = bem::interior_surface_gradient(mesh, sol);
    double surface = 0.0;
    for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
      const Eigen::Vector3d c = mesh.face_centroids().row(f).transpose();
      if (c.head<2>().cwiseAbs().maxCoeff() > 1.0 || std::abs(c.z()) < t / 4) continue;
      const double h = ref::paper_thickness(kPaper, ref::inverse_thickness(kPaper, trace(g.face_gradient, f)));
      surface = std::max(surface, std::abs(h - t) / t);
    }
    Eigen::MatrixX3d mid(3, 3);
    mid << 0, 0, 0, 0.5, -0.3, 0.1, -0.7, 0.2, -0.12;
    const auto field = bem::evaluate_potential(mesh, sol, mid);
    double interior = 0.0;
    for (Eigen::Index p = 0; p < 3; ++p)
      interior = std::max(interior, std::abs(ref::paper_thickness(kPaper, ref::inverse_thickness(kPaper, trace(field.gradient, p))) - t) / t);
    std::printf("| %.2f | %.1f | %ld | %.2e | %.2e | %.1f |\n", edge, kParameters.kappa * edge,
                long(mesh.num_faces()), surface, interior, seconds(t0));
    std::fflush(stdout);
  }
}
}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  if (which == "ball" || which == "all") ball();
  if (which == "shell" || which == "all") shell();
  if (which == "plate" || which == "all") plate();
  return 0;
}
