// Fast-path benchmark (docs/benchmarks.md): builds a sphere, a plate or a thin-walled box of
// about the requested number of faces at the default element size (longest edge 1.5·a·h0),
// solves with the dense and/or the hierarchical-matrix path and prints one JSON line per run:
//
//   bench_fast_path sphere|plate|box FACES [dense|hmatrix|both] [--tolerance T] [--aca E]
//                   [--leaf L] [--eta H] [--single|--double] [--block B] [--coarse C] [--right]
//                   [--far-field auto|hmatrix|nested] [--nested-min-cluster S]
//   bench_fast_path file MESH H0 [dense|hmatrix|both] [options as above]
//                   (a mesh file as the solver mesh, no refinement; no closed form, error 0)
//   bench_fast_path entry-costs FACES     (where a row of the operators spends its time)
//   bench_fast_path nested-bases sphere|box FACES [--aca E] [--eta H] [--leaf L] [--basis T]
//                   (the Laplace far field in the H² form against the H-matrix's factors)
//   bench_fast_path nested-far-field sphere|box FACES [--aca E] [--basis T] [--min-cluster S]
//   [--compare]
//                   (the H² far field built from the kernel, never holding the H-matrix)
//   bench_fast_path interior sphere|box FACES POINTS [--solve] [--order P] [--theta T]
//                   [--leaf L] [--negligible D] [--reference M] [--sweep]      (evaluate_potential
//                   on a grid: treecode vs direct)
//
// Fields: shape, faces, solver, times (mesh, assemble, solve, features; seconds), iterations,
// residual, cpu_seconds (user + system of all threads for the solve and features),
// peak_rss_mb (whole process), operator_mb, compression (H-matrix stored/dense
// entries of the Laplace part), error (relative error of the thickness against the closed
// form: f_h at the ball's centre; paper thickness h_f = h0(1/f_h − a) of the faces in the
// middle of a wall for the plate and the box) and, with `both`, the largest differences
// between the paths, ‖dense − hmatrix‖/‖dense‖ over all faces and directions (phi, q,
// thickness).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <sys/resource.h>

#include "bem/solve/dense_transmission_solver.hpp"
#include "bem/operators/galerkin_operators.hpp"
#include "bem/operators/galerkin_block_generator.hpp"
#include "bench/nested_cluster_basis.hpp"
#include "bem/hmatrix/nested_far_field.hpp"
#include "bem/solve/hmatrix_transmission_solver.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "bem/evaluate/surface_gradient.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "core/heap_retention.hpp"
#include "core/huge_pages.hpp"
#include "core/memory.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
namespace ref = bemshape::testing;

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr double kA = 0.2;

struct Problem {
  geometry::SurfaceMesh mesh;
  double h0 = 0.3;
  /// Faces whose thickness is compared with `thickness` (walls far from edges).
  std::vector<Eigen::Index> probe_faces;
  double thickness = 0.0;  ///< exact h_f on the probe faces (plate, box)
  double ball_radius = 0.0;
};

/// Sphere R = 0.5 with h0 chosen so the mesh's edge is the default rule's.
Problem sphere(double faces) {
  Problem p;
  const int frequency = std::max(1, int(std::lround(std::sqrt(faces / 20.0))));
  p.mesh = geometry::make_geodesic_sphere(0.5, frequency);
  p.h0 = p.mesh.max_edge_length() / (1.5 * kA);
  p.ball_radius = 0.5;
  return p;
}

/// Square plate L × L × h0, h0 = 0.3, edge 0.09: faces ≈ 4L²/0.09² (two big faces).
Problem plate(double faces) {
  Problem p;
  const double edge = 1.5 * kA * p.h0;
  const double side = std::max(4.0 * p.h0, edge * std::sqrt(faces / 4.0));
  p.mesh = geometry::make_box(Eigen::Vector3d(-side / 2, -side / 2, -p.h0 / 2),
                              Eigen::Vector3d(side / 2, side / 2, p.h0 / 2), edge);
  p.thickness = p.h0;
  const Eigen::MatrixX3d& c = p.mesh.face_centroids();
  for (Eigen::Index f = 0; f < c.rows(); ++f)
    if (std::abs(c(f, 0)) < 1.0 * p.h0 && std::abs(c(f, 1)) < 1.0 * p.h0) p.probe_faces.push_back(f);
  return p;
}

/// Hollow cube, outer side L, wall h0 = 0.3, edge 0.09: faces ≈ 2 · 6L²/(0.09²/2).
Problem box(double faces) {
  Problem p;
  const double edge = 1.5 * kA * p.h0;
  const double side = std::max(6.0 * p.h0, edge * std::sqrt(faces / 24.0));
  p.mesh = geometry::make_hollow_box(Eigen::Vector3d::Constant(side / 2), p.h0, edge);
  p.thickness = p.h0;
  const Eigen::MatrixX3d& c = p.mesh.face_centroids();
  for (Eigen::Index f = 0; f < c.rows(); ++f)  // middle of the top wall, both sides
    if (std::abs(c(f, 0)) < p.h0 && std::abs(c(f, 1)) < p.h0 && c(f, 2) > 0) p.probe_faces.push_back(f);
  return p;
}

/// A mesh file used as the solver mesh as it is (read, repaired and oriented like the
/// `thickness` command's input, not refined), with characteristic length h0: for the cost of
/// meshes the generators do not make, such as the remeshed tessellations of CAD exports
/// (`thickness --solver-output mesh.ply` writes one).
Problem from_file(const std::string& path, double h0) {
  Problem p;
  p.mesh = geometry::prepare_mesh_file(path).mesh;
  p.h0 = h0;
  return p;
}

/// h_f per face from the surface gradient's trace.
Eigen::VectorXd face_thickness(const geometry::SurfaceMesh& mesh, const bem::BoundarySolution& s,
                               double h0) {
  const auto g = bem::interior_surface_gradient(mesh, s);
  Eigen::VectorXd h(mesh.num_faces());
  for (Eigen::Index f = 0; f < h.size(); ++f) {
    const double f_h = h0 * h0 * (g.face_gradient(f, 0) + g.face_gradient(f, 4) + g.face_gradient(f, 8));
    h(f) = h0 * (1.0 / f_h - kA);
  }
  return h;
}

struct Run {
  bem::BoundarySolution solution;
  Eigen::VectorXd thickness;
  double assemble = 0, solve = 0, features = 0, error = 0;
};

Run run(const Problem& p, const std::string& solver, const bem::HMatrixSolverOptions& options) {
  const auto parameters = bem::TransmissionParameters::from_shape(p.h0, kA);
  Run r;
  r.solution = solver == "dense" ? bem::solve_transmission_dense(p.mesh, parameters)
                                 : bem::solve_transmission_hmatrix(p.mesh, parameters, options);
  r.assemble = r.solution.report.assembly_seconds;
  r.solve = r.solution.report.solve_seconds;
  const auto t0 = Clock::now();
  r.thickness = face_thickness(p.mesh, r.solution, p.h0);
  if (p.ball_radius > 0) {
    const ref::PdeParameters pde{p.h0, kA};
    const double exact = ref::inverse_thickness(pde, 3.0 * ref::ball_solution(pde, p.ball_radius).A);
    const auto field = bem::evaluate_potential(p.mesh, r.solution, Eigen::MatrixX3d::Zero(1, 3));
    const double f_h = p.h0 * p.h0 * (field.gradient(0, 0) + field.gradient(0, 4) + field.gradient(0, 8));
    r.error = std::abs(f_h - exact) / exact;
  } else {
    for (const Eigen::Index f : p.probe_faces)
      r.error = std::max(r.error, std::abs(r.thickness(f) - p.thickness) / p.thickness);
  }
  r.features = seconds(t0);
  return r;
}

/// ‖a − b‖_F/‖a‖_F (a the dense reference).
/// CPU time of the process so far (user + system, all threads) [s]: with other work on the
/// machine it says more about the cost than wall times do.
double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / a.norm();
}

}  // namespace

/// CPU time of the calling thread [s]: entry costs measured by it do not count the time other
/// processes on the machine take from this thread (clock_gettime costs about 0.05 µs).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Where a row of the Galerkin operators spends its time, on the sphere of `faces` faces at
/// the default element size: pairs per row and microseconds per entry in each class of the
/// entry generator's rule selection (bem/operators/galerkin_operators.hpp), Yukawa and Laplace.
int entry_costs(double faces) {
  const Problem p = sphere(faces);
  const auto parameters = bem::TransmissionParameters::from_shape(p.h0, kA);
  const auto panels = bem::make_panels(p.mesh);
  const bem::GalerkinOperators<bem::YukawaKernel> yukawa(bem::YukawaKernel{parameters.kappa}, panels);
  const bem::GalerkinOperators<bem::LaplaceKernel> laplace(bem::LaplaceKernel{}, panels);
  const char* names[] = {"touching", "near (eta < 2)", "middle (eta 2-4)", "attenuated", "far"};
  double yukawa_time[5] = {}, laplace_time[5] = {};
  long count[5] = {}, dropped = 0;
  double checksum = 0.0;
  double subdivided_yukawa_time = 0.0, subdivided_laplace_time = 0.0;  // printed, so the compiler cannot drop an entry whose value is unused
  const int rows = 50;
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < Eigen::Index(panels.size()); ++j) {
      const bem::Panel& a = panels[size_t(i)];
      const bem::Panel& b = panels[size_t(j)];
      const double distance = (a.centroid - b.centroid).norm();
      const double ratio = distance / std::max(a.diameter, b.diameter);
      const double attenuation =
          std::exp(-parameters.kappa * std::max(0.0, distance - a.radius - b.radius));
      int c = 4;
      if (bem::GalerkinOperators<bem::LaplaceKernel>::touching(a, b)) c = 0;
      else if (ratio < 2.0) c = 1;
      else if (attenuation < bem::YukawaAttenuation::cheap_rule && ratio >= 1.5) c = 3;
      else if (ratio < 4.0) c = 2;
      double t0 = thread_cpu_seconds();
      const auto y = yukawa.entry(i, j);
      const double ty = thread_cpu_seconds() - t0;
      t0 = thread_cpu_seconds();
      const auto l = laplace.entry(i, j);
      const double tl = thread_cpu_seconds() - t0;
      checksum += l.single_layer + l.double_layer + y.single_layer + y.double_layer;
      if (c == 0) {
        // The scheme touching pairs used before the Sauter–Schwab rules, for comparison: the
        // test panel split into 4 (16 when κ·diameter > 4) × the 6-point rule, times the
        // polar panel integrals of the trial panel.
        const int levels = parameters.kappa * a.diameter <= 4.0 ? 1 : 2;
        const auto& rule = bem::symmetric_triangle_rule(4);
        t0 = thread_cpu_seconds();
        const auto yo = yukawa.outer_rule_entry(a, b, levels, rule);
        subdivided_yukawa_time += thread_cpu_seconds() - t0;
        t0 = thread_cpu_seconds();
        const auto lo = laplace.outer_rule_entry(a, b, 1, rule);
        subdivided_laplace_time += thread_cpu_seconds() - t0;
        checksum += yo.single_layer + lo.single_layer;
      }
      if (y.single_layer == 0.0 && y.double_layer == 0.0 && attenuation < bem::YukawaAttenuation::negligible) {
        ++dropped;
        laplace_time[4] += tl;
        ++count[4];
        continue;
      }
      yukawa_time[c] += ty;
      laplace_time[c] += tl;
      ++count[c];
    }
  std::printf("sphere, %ld faces, kappa*h = %.2f: per row, %d rows timed (thread CPU time)\n",
              long(panels.size()), parameters.kappa * p.mesh.max_edge_length(), rows);
  std::printf("| pair class | pairs per row | Yukawa us/entry | Yukawa us/row | Laplace us/entry | Laplace us/row |\n|---|---|---|---|---|---|\n");
  for (int c = 0; c < 5; ++c) {
    const double per_row = double(count[c]) / rows;
    const double y = count[c] ? 1e6 * yukawa_time[c] / double(count[c]) : 0.0;
    const double l = count[c] ? 1e6 * laplace_time[c] / double(count[c]) : 0.0;
    std::printf("| %s | %.1f | %.2f | %.0f | %.2f | %.0f |\n", names[c], per_row, y, y * per_row, l, l * per_row);
  }
  if (count[0] > 0) {
    const double per_row = double(count[0]) / rows;
    const double y = 1e6 * subdivided_yukawa_time / double(count[0]);
    const double l = 1e6 * subdivided_laplace_time / double(count[0]);
    std::printf("| touching, subdivided outer rule (before) | %.1f | %.2f | %.0f | %.2f | %.0f |\n",
                per_row, y, y * per_row, l, l * per_row);
  }
  std::printf("(far includes %.1f pairs per row whose Yukawa entry is dropped; checksum %.6e)\n",
              double(dropped) / rows, checksum);
  return 0;
}

/// evaluate_potential at the nodes of a grid of about `points` nodes over the bounding box
/// of a sphere or box of `faces` faces (enlarged by 5%, as `features --grid` covers the
/// part): the tree sums (bem/evaluate/laplace_treecode.hpp, yukawa_cutoff_sum.hpp)
/// timed on every node, the direct sums over every panel on `reference` nodes spread over
/// the grid, their cost extrapolated to all nodes and their results compared. The boundary
/// data are the ball's closed form s = A·x inside (φ = A·x at the centroids, q = A·n) unless
/// --solve asks for the H-matrix solution. One JSON line:
///   seconds, cpu_seconds: the tree evaluation of all nodes (wall, user + system);
///   laplace_panel_integrals, laplace_expansions, yukawa_panel_integrals: its work;
///   direct_*: the same for the direct sums, extrapolated from the reference nodes;
///   error: largest difference on the reference nodes, relative to the largest value there
///   (s, gradient), absolute (winding), and the number of nodes whose inside flag differs.
/// --sweep repeats the tree evaluation for several (p, θ) (the table behind
/// LaplaceTreecodeParameters::for_tolerance), one line each, against one direct reference.
int interior(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: bench_fast_path interior sphere|box FACES POINTS [--solve] "
                         "[--order P] [--theta T] [--leaf L] [--negligible D] [--reference M] "
                         "[--sweep]\n");
    return 2;
  }
  const std::string shape = argv[2];
  const Problem p = shape == "sphere" ? sphere(std::atof(argv[3])) : box(std::atof(argv[3]));
  const double requested = std::atof(argv[4]);
  bool solve = false, sweep = false;
  long reference_points = 1000;
  bem::PotentialEvaluationOptions options;
  for (int i = 5; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--solve") solve = true;
    else if (a == "--sweep") sweep = true;
    else if (a == "--order" && i + 1 < argc) options.treecode.order = std::atoi(argv[++i]);
    else if (a == "--theta" && i + 1 < argc) options.treecode.theta = std::atof(argv[++i]);
    else if (a == "--reference" && i + 1 < argc) reference_points = std::atol(argv[++i]);
    else if (a == "--leaf" && i + 1 < argc) options.leaf_size = std::atol(argv[++i]);
    else if (a == "--negligible" && i + 1 < argc) options.yukawa_negligible = std::atof(argv[++i]);
    else {
      std::fprintf(stderr, "bench_fast_path: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  const auto parameters = bem::TransmissionParameters::from_shape(p.h0, kA);
  bem::BoundarySolution solution;
  if (solve) {
    solution = bem::solve_transmission_hmatrix(p.mesh, parameters, {});
  } else {
    const double A = ref::ball_solution(ref::PdeParameters{p.h0, kA}, 0.5).A;
    solution.phi = A * p.mesh.face_centroids();
    solution.q = A * p.mesh.face_normals();
    solution.parameters = parameters;
  }
  // The grid: n³ nodes over the bounding box enlarged by 5%.
  const Eigen::Vector3d lo = p.mesh.vertices().colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = p.mesh.vertices().colwise().maxCoeff().transpose();
  const Eigen::Vector3d centre = 0.5 * (lo + hi), half = 0.525 * (hi - lo);
  const long n = std::max(2L, std::lround(std::cbrt(requested)));
  Eigen::MatrixX3d grid(n * n * n, 3);
  for (long i = 0, row = 0; i < n; ++i)
    for (long j = 0; j < n; ++j)
      for (long k = 0; k < n; ++k, ++row)
        grid.row(row) = (centre + half.cwiseProduct(Eigen::Vector3d(double(i), double(j), double(k)) *
                                                        (2.0 / double(n - 1)) -
                                                    Eigen::Vector3d::Ones()))
                            .transpose();
  // The direct sums on every (rows / reference)-th node.
  const long m = std::min<long>(reference_points, long(grid.rows()));
  const long stride = long(grid.rows()) / m;
  Eigen::MatrixX3d sample(m, 3);
  for (long i = 0; i < m; ++i) sample.row(i) = grid.row(i * stride);
  bem::PotentialEvaluationOptions direct_options;
  direct_options.direct = true;
  const double cpu1 = cpu_seconds();
  const auto t1 = Clock::now();
  const bem::PotentialField direct = bem::evaluate_potential(p.mesh, solution, sample, {}, direct_options);
  const double scale = double(grid.rows()) / double(m);
  const double direct_wall = seconds(t1) * scale, direct_cpu = (cpu_seconds() - cpu1) * scale;

  std::vector<bem::LaplaceTreecodeParameters> settings{options.treecode};
  if (sweep)
    settings = {{4, 0.3}, {6, 0.3}, {8, 0.3}, {10, 0.3}, {12, 0.3}, {14, 0.3},
                {8, 0.5}, {10, 0.5}, {14, 0.5}, {10, 0.4}, {12, 0.4}};
  for (const bem::LaplaceTreecodeParameters& setting : settings) {
    options.treecode = setting;
    const double cpu0 = cpu_seconds();
    const auto t0 = Clock::now();
    const bem::PotentialField fast = bem::evaluate_potential(p.mesh, solution, grid, {}, options);
    const double wall = seconds(t0), cpu = cpu_seconds() - cpu0;
    long inside = 0;
    for (const char c : fast.inside) inside += c;
    double ds = 0, dg = 0, dw = 0, smax = 0, gmax = 0;
    long flips = 0;
    for (long i = 0; i < m; ++i) {
      const long r = i * stride;
      smax = std::max(smax, direct.s.row(i).norm());
      gmax = std::max(gmax, direct.gradient.row(i).norm());
      ds = std::max(ds, (direct.s.row(i) - fast.s.row(r)).norm());
      dg = std::max(dg, (direct.gradient.row(i) - fast.gradient.row(r)).norm());
      dw = std::max(dw, std::abs(direct.winding(i) - fast.winding(r)));
      flips += direct.inside[size_t(i)] != fast.inside[size_t(r)];
    }
    std::printf("{\"shape\": \"%s\", \"faces\": %ld, \"points\": %ld, \"inside\": %ld, "
                "\"data\": \"%s\", \"order\": %d, \"theta\": %.3g, \"leaf\": %ld, "
                "\"negligible\": %.0e, \"seconds\": %.2f, \"cpu_seconds\": %.2f, "
                "\"laplace_panel_integrals\": %.4g, \"laplace_expansions\": %.4g, "
                "\"yukawa_panel_integrals\": %.4g, \"reference_points\": %ld, "
                "\"direct_seconds\": %.4g, \"direct_cpu_seconds\": %.4g, "
                "\"direct_laplace_panel_integrals\": %.4g, \"direct_yukawa_panel_integrals\": %.4g, "
                "\"error\": {\"s\": %.2e, \"gradient\": %.2e, \"winding\": %.2e, "
                "\"inside_flips\": %ld}, \"moment_mb\": %.1f, \"peak_rss_mb\": %.1f}\n",
                shape.c_str(), long(p.mesh.num_faces()), long(grid.rows()), inside,
                solve ? "hmatrix solution" : "closed form", setting.order, setting.theta,
                long(options.leaf_size), options.yukawa_negligible, wall, cpu,
                double(fast.cost.laplace_panel_integrals), double(fast.cost.laplace_expansions),
                double(fast.cost.yukawa_panel_integrals), m, direct_wall, direct_cpu,
                double(direct.cost.laplace_panel_integrals) * scale,
                double(direct.cost.yukawa_panel_integrals) * scale, ds / smax, dg / gmax, dw, flips,
                double(fast.cost.moment_bytes) / 1e6, double(peak_resident_bytes()) / 1e6);
    std::fflush(stdout);
  }
  return 0;
}

/// The best of three wall times of apply(y), y += A x for three vectors (the three
/// directions of a solve) on n rows, y zeroed before each run [s].
template <class Apply>
double best_product_seconds(Eigen::Index n, const Apply& apply) {
  double best = 1e300;
  for (int repeat = 0; repeat < 3; ++repeat) {
    Eigen::MatrixXd y = Eigen::MatrixXd::Zero(n, 3);
    const auto start = Clock::now();
    apply(y);
    best = std::min(best, seconds(start));
  }
  return best;
}

/// The Laplace row's far field [−K0 | V0] in the H² form against the H-matrix, on the sphere
/// or the thin-walled box of `faces` faces (bench/nested_cluster_basis.hpp):
///
///   bench_fast_path nested-bases sphere|box FACES [--aca E] [--eta H] [--leaf L] [--basis T]
///
/// builds the solver's H-matrix (narrow factors, its bytes), then the same operator with
/// factors in double precision (ACA at E, default 1e−8), converts its low-rank blocks to
/// nested bases at tolerance T (default E) and prints the entries of both forms, the ranks
/// of the bases by tree level and the conversion's error bound ‖A_b − Q S Pᵀ‖/‖A_b‖ over a
/// sample of blocks, and the time of one product with three vectors: the solver's H-matrix
/// and the double-precision one (near and far field), the H² form (far field only).
int nested_bases(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: bench_fast_path nested-bases sphere|box FACES [--aca E] [--eta H] [--leaf L] [--basis T]\n");
    return 2;
  }
  const std::string shape = argv[2];
  double aca = 1e-8, eta = bem::kDefaultAdmissibility, basis_tolerance = 0.0;
  Eigen::Index leaf = bem::ClusterTree::kDefaultLeafSize;
  for (int i = 4; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--aca") aca = std::atof(argv[i + 1]);
    else if (a == "--eta") eta = std::atof(argv[i + 1]);
    else if (a == "--leaf") leaf = std::atol(argv[i + 1]);
    else if (a == "--basis") basis_tolerance = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "bench_fast_path: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  if (basis_tolerance == 0.0) basis_tolerance = aca;
  const Problem p = shape == "sphere" ? sphere(std::atof(argv[3])) : box(std::atof(argv[3]));
  const auto panels = bem::make_panels(p.mesh);
  const bem::ClusterTree tree(panels, leaf);
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, panels,
                                                                  tree.permutation());
  // Products with three vectors (the three directions of a solve), the best of three runs.
  const Eigen::Index n = p.mesh.num_faces();
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(n, 6);
  const auto product_seconds = [&](const auto& apply) { return best_product_seconds(n, apply); };
  bem::HierarchicalMatrixStats narrow;
  double solver_product = 0.0;
  {
    const bem::HierarchicalMatrix solver_form(tree, generator, {aca, eta, true, true, true});
    narrow = solver_form.stats();
    solver_product = product_seconds([&](Eigen::MatrixXd& y) { solver_form.multiply_add(x, y); });
  }
  auto t0 = Clock::now();
  const bem::HierarchicalMatrix exact_factors(tree, generator, {aca, eta, false, false, false});
  const double assemble_seconds = seconds(t0);
  // The same low-rank blocks once more (the H-matrix keeps its factors to itself): the
  // conversion's input, computed as the H-matrix computes them.
  const auto blocks = bench::far_field_low_rank_blocks(tree, generator, aca, eta);
  std::uint64_t h_entries = 0;
  for (const auto& b : blocks) h_entries += std::uint64_t(b.U.size() + b.V.size());
  t0 = Clock::now();
  const bench::NestedClusterBasis h2(tree, blocks, 2, basis_tolerance);
  const double convert_seconds = seconds(t0);
  const auto storage = h2.storage();
  const double double_product = product_seconds([&](Eigen::MatrixXd& y) { exact_factors.multiply_add(x, y); });
  const double h2_product = product_seconds([&](Eigen::MatrixXd& y) { h2.multiply_add(tree, x, y); });

  // Ranks by tree level (level 0: the root).
  std::vector<int> level(tree.clusters().size(), 0);
  for (std::size_t c = 0; c < level.size(); ++c)
    if (!tree.clusters()[c].is_leaf()) {
      level[std::size_t(tree.clusters()[c].first_child)] = level[c] + 1;
      level[std::size_t(tree.clusters()[c].first_child + 1)] = level[c] + 1;
    }
  const int levels = 1 + *std::max_element(level.begin(), level.end());
  std::string by_level;
  for (int l = 0; l < levels; ++l) {
    double row_sum = 0, col_sum = 0, size_sum = 0;
    long count = 0;
    Eigen::Index row_max = 0, col_max = 0;
    for (std::size_t c = 0; c < level.size(); ++c) {
      if (level[c] != l || h2.rows().rank[c] + h2.columns().rank[c] == 0) continue;
      ++count;
      size_sum += double(tree.clusters()[c].size());
      row_sum += double(h2.rows().rank[c]);
      col_sum += double(h2.columns().rank[c]);
      row_max = std::max(row_max, h2.rows().rank[c]);
      col_max = std::max(col_max, h2.columns().rank[c]);
    }
    if (count == 0) continue;
    char row[256];
    std::snprintf(row, sizeof row,
                  "%s{\"level\": %d, \"clusters\": %ld, \"mean_size\": %.0f, \"row_rank_mean\": %.1f, "
                  "\"row_rank_max\": %ld, \"column_rank_mean\": %.1f, \"column_rank_max\": %ld}",
                  by_level.empty() ? "" : ", ", l, count, size_sum / double(count), row_sum / double(count),
                  long(row_max), col_sum / double(count), long(col_max));
    by_level += row;
  }
  // The conversion's error on about 400 blocks spread over the list (sizes vary along it).
  const std::size_t stride = std::max<std::size_t>(1, blocks.size() / 400);
  double worst = 0.0, sum = 0.0;
  long sampled = 0;
  for (std::size_t b = 0; b < blocks.size(); b += stride, ++sampled) {
    const double e = bench::nested_basis_error_bound(blocks[b].U, blocks[b].V, h2.rows().expand(tree, h2.row_cluster(b)),
                                                   h2.columns().expand(tree, h2.column_cluster(b)));
    worst = std::max(worst, e);
    sum += e;
  }
  std::printf("{\"shape\": \"%s\", \"faces\": %ld, \"leaf\": %ld, \"eta\": %.3g, \"aca\": %.1e, \"basis_tolerance\": %.1e, "
              "\"low_rank_blocks\": %zu, \"solver_far_field_mb\": %.1f, \"solver_factor_entries\": %llu, "
              "\"double_factor_entries\": %llu, \"h2_entries\": %llu, \"h2_leaf_basis_entries\": %llu, "
              "\"h2_transfer_entries\": %llu, \"h2_coupling_entries\": %llu, \"h2_factored_coupling_entries\": %llu, "
              "\"h2_entries_factored_couplings\": %llu, \"h2_single_mb\": %.1f, "
              "\"assemble_seconds\": %.1f, \"convert_seconds\": %.1f, \"error_bound_max\": %.2e, "
              "\"error_bound_mean\": %.2e, \"sampled_blocks\": %ld, \"product_seconds\": {\"solver_hmatrix\": %.3f, "
              "\"double_hmatrix\": %.3f, \"h2_far_field\": %.3f}, \"peak_rss_mb\": %.1f, \"levels\": [%s]}\n",
              shape.c_str(), long(p.mesh.num_faces()), long(leaf), eta, aca, basis_tolerance, blocks.size(),
              double(narrow.low_rank_bytes) / 1e6, (unsigned long long)narrow.low_rank_entries,
              (unsigned long long)h_entries, (unsigned long long)storage.entries(),
              (unsigned long long)storage.leaf_basis_entries, (unsigned long long)storage.transfer_entries,
              (unsigned long long)storage.coupling_entries, (unsigned long long)storage.factored_coupling_entries,
              (unsigned long long)storage.entries_with_factored_couplings(),
              4.0 * double(storage.entries_with_factored_couplings()) / 1e6,
              assemble_seconds, convert_seconds, worst, sum / double(sampled), sampled, solver_product,
              double_product, h2_product, double(peak_resident_bytes()) / 1e6, by_level.c_str());
  return 0;
}

/// The Laplace row's far field [−K0 | V0] in the H² form built from the kernel
/// (bem/hmatrix/nested_far_field.hpp), on the sphere or the thin-walled box:
///
///   bench_fast_path nested-far-field sphere|box FACES [--aca E] [--basis T] [--min-cluster S]
///   [--compare]
///
/// prints the construction's time (row and column sides), the entries and bytes, the peak
/// RSS after the construction (nothing else large is held: the tree, the panels and the
/// generator's tables), the time of one far-field product with three vectors (best of
/// three), and ‖A_b − Q S Pᵀ‖/‖A_b‖ against the operator's entries on about 200 blocks.
/// With --compare, afterwards, the solver's H-matrix (narrow factors) for its far-field bytes
/// and product time. With --min-cluster S (default 0) the blocks with a cluster of fewer
/// than S panels are H-matrix factors instead (small_low_rank_mb, small_dense_mb); the H²
/// form's uncompressed blocks (uncompressed_blocks) are counted, not stored.
int nested_far_field(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: bench_fast_path nested-far-field sphere|box FACES [--aca E] [--basis T] "
                 "[--min-cluster S] [--compare]\n");
    return 2;
  }
  const std::string shape = argv[2];
  bem::NestedFarFieldOptions options;
  bool compare = false;
  Eigen::Index min_cluster = 0;
  for (int i = 4; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--aca" && i + 1 < argc)
      options.aca_tolerance = std::atof(argv[++i]);
    else if (a == "--min-cluster" && i + 1 < argc)
      min_cluster = std::atol(argv[++i]);
    else if (a == "--basis" && i + 1 < argc)
      options.basis_tolerance = std::atof(argv[++i]);
    else if (a == "--compare")
      compare = true;
    else {
      std::fprintf(stderr, "bench_fast_path: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  const Problem p = shape == "sphere" ? sphere(std::atof(argv[3])) : box(std::atof(argv[3]));
  const auto panels = bem::make_panels(p.mesh);
  const bem::ClusterTree tree(panels);
  const bem::GalerkinBlockGenerator<bem::LaplaceKernel> generator(bem::LaplaceKernel{}, panels,
                                                                  tree.permutation());
  const bem::BlockPartition partition = bem::partition_blocks(tree);
  // Blocks with a cluster of fewer than min_cluster panels stay in the H-matrix's form.
  bem::BlockPartition small;
  std::vector<bem::BlockIndex> large;
  for (const bem::BlockIndex& b : partition.admissible)
    (std::min(tree.cluster(b.rows).size(), tree.cluster(b.cols).size()) < min_cluster
         ? small.admissible
         : large)
        .push_back(b);
  const double rss_before = double(peak_resident_bytes());
  auto t0 = Clock::now();
  const bem::NestedFarField h2(tree, large, generator, options);
  const double build_seconds = seconds(t0);
  const double rss_after = double(peak_resident_bytes());
  t0 = Clock::now();
  const bem::HierarchicalMatrix small_blocks(
      tree, tree, small, generator,
      {options.aca_tolerance, bem::kDefaultAdmissibility, true, true, true});
  const double small_seconds = seconds(t0);
  const Eigen::Index n = p.mesh.num_faces();
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(n, 6);
  const auto product_seconds = [&](const auto& apply) { return best_product_seconds(n, apply); };
  const double h2_product = product_seconds([&](Eigen::MatrixXd& y) { h2.multiply_add(x, y); });
  const double small_product =
      product_seconds([&](Eigen::MatrixXd& y) { small_blocks.multiply_add(x, y); });
  const std::size_t stride = std::max<std::size_t>(1, h2.blocks().size() / 200);
  double worst = 0.0;
  for (std::size_t b = 0; b < h2.blocks().size(); b += stride) {
    const bem::Cluster& t = tree.cluster(h2.blocks()[b].rows);
    const bem::Cluster& s = tree.cluster(h2.blocks()[b].cols);
    if (t.size() * s.size() > 4000000)
      continue;  // the sample's blocks in explicit form: 64 MB at most
    Eigen::MatrixXd exact(t.size(), 2 * s.size());
    generator.fill(t.begin, t.end, s.begin, s.end, exact);
    worst = std::max(worst, (exact - h2.block(b)).norm() / exact.norm());
  }
  double solver_far_mb = 0.0, solver_product = 0.0, solver_seconds = 0.0;
  if (compare) {
    bem::BlockPartition far;
    far.admissible = partition.admissible;
    t0 = Clock::now();
    const bem::HierarchicalMatrix solver_form(
        tree, tree, far, generator,
        {options.aca_tolerance, bem::kDefaultAdmissibility, true, true, true});
    solver_seconds = seconds(t0);
    solver_far_mb = double(solver_form.stats().low_rank_bytes) / 1e6;
    solver_product = product_seconds([&](Eigen::MatrixXd& y) { solver_form.multiply_add(x, y); });
  }
  const bem::NestedFarFieldStats& st = h2.stats();
  std::printf(
      "{\"shape\": \"%s\", \"faces\": %ld, \"aca\": %.1e, \"basis_tolerance\": %.1e, "
      "\"blocks\": %zu, \"uncompressed_blocks\": %zu, \"build_seconds\": %.1f, \"row_seconds\": "
      "%.1f, "
      "\"column_seconds\": %.1f, \"aca_thread_seconds\": %.1f, \"basis_thread_seconds\": %.1f, "
      "\"basis_r2c\": %.3g, \"leaf_basis_entries\": %llu, \"transfer_entries\": %llu, "
      "\"coupling_entries\": %llu, \"h2_mb\": %.1f, \"max_row_rank\": %ld, \"max_column_rank\": "
      "%ld, "
      "\"h2_product_seconds\": %.3f, \"error_max\": %.2e, \"peak_rss_before_mb\": %.1f, "
      "\"peak_rss_after_build_mb\": %.1f, \"solver_far_field_mb\": %.1f, "
      "\"solver_far_field_seconds\": %.1f, "
      "\"solver_far_field_product_seconds\": %.3f, \"min_cluster\": %ld, \"small_blocks\": %zu, "
      "\"small_low_rank_mb\": %.1f, \"small_dense_mb\": %.1f, \"small_seconds\": %.1f, "
      "\"small_product_seconds\": %.3f}\n",
      shape.c_str(), long(n), options.aca_tolerance, options.basis_tolerance, st.blocks,
      st.uncompressed_blocks, build_seconds, st.row_seconds, st.column_seconds, st.aca_seconds,
      st.basis_seconds, double(st.basis_flops), (unsigned long long)st.leaf_basis_entries,
      (unsigned long long)st.transfer_entries, (unsigned long long)st.coupling_entries,
      double(st.bytes) / 1e6, long(st.max_row_rank), long(st.max_column_rank), h2_product, worst,
      rss_before / 1e6, rss_after / 1e6, solver_far_mb, solver_seconds, solver_product,
      long(min_cluster), small.admissible.size(), double(small_blocks.stats().low_rank_bytes) / 1e6,
      double(small_blocks.stats().dense_bytes) / 1e6, small_seconds, small_product);
  return 0;
}

int benchmark(int argc, char** argv) {
  bemshape::restart_with_heap_huge_pages(argv);  // as the bemshape executable does
  bemshape::retain_freed_heap_memory();
  bemshape::pad_heap_growth();
  if (argc == 3 && std::string(argv[1]) == "entry-costs") return entry_costs(std::atof(argv[2]));
  if (argc >= 2 && std::string(argv[1]) == "interior") return interior(argc, argv);
  if (argc >= 2 && std::string(argv[1]) == "nested-bases") return nested_bases(argc, argv);
  if (argc >= 2 && std::string(argv[1]) == "nested-far-field")
    return nested_far_field(argc, argv);
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_fast_path sphere|plate|box FACES [dense|hmatrix|both] "
                         "[--tolerance T] [--aca E] [--leaf L] [--eta H] [--single|--double] [--block B] [--coarse C]\n");
    return 2;
  }
  const std::string shape = argv[1];
  const bool from_mesh_file = shape == "file";
  if (from_mesh_file && argc < 4) {
    std::fprintf(stderr, "usage: bench_fast_path file MESH H0 [dense|hmatrix|both] [options]\n");
    return 2;
  }
  const double faces = from_mesh_file ? 0.0 : std::atof(argv[2]);
  std::string solver = "hmatrix";
  bem::HMatrixSolverOptions options;
  for (int i = from_mesh_file ? 4 : 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "dense" || a == "hmatrix" || a == "both") solver = a;
    else if (a == "--tolerance" && i + 1 < argc) options.tolerance = std::atof(argv[++i]);
    else if (a == "--aca" && i + 1 < argc) options.aca_tolerance = std::atof(argv[++i]);
    else if (a == "--leaf" && i + 1 < argc) options.leaf_size = std::atol(argv[++i]);
    else if (a == "--eta" && i + 1 < argc) options.eta = std::atof(argv[++i]);
    else if (a == "--right") options.preconditioner_side = linalg::PreconditionerSide::right;
    else if (a == "--single") options.single_precision = true;
    else if (a == "--double") options.single_precision = false;
    else if (a == "--block" && i + 1 < argc) options.preconditioner_block = std::atol(argv[++i]);
    else if (a == "--coarse" && i + 1 < argc) options.coarse_cluster = std::atol(argv[++i]);
    else if (a == "--far-field" && i + 1 < argc) {
      const std::string f = argv[++i];
      if (f != "nested" && f != "hmatrix" && f != "auto") {
        std::fprintf(stderr,
                     "bench_fast_path: --far-field must be auto, hmatrix or nested, got %s\n",
                     f.c_str());
        return 2;
      }
      options.far_field = f == "nested"    ? bem::HMatrixSolverOptions::FarField::nested
                          : f == "hmatrix" ? bem::HMatrixSolverOptions::FarField::hmatrix
                                           : bem::HMatrixSolverOptions::FarField::automatic;
    } else if (a == "--nested-min-cluster" && i + 1 < argc)
      options.nested_min_cluster = std::atol(argv[++i]);
    else {
      std::fprintf(stderr, "bench_fast_path: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  const auto t0 = Clock::now();
  const Problem p = from_mesh_file    ? from_file(argv[2], std::atof(argv[3]))
                    : shape == "sphere" ? sphere(faces)
                    : shape == "plate"  ? plate(faces)
                                        : box(faces);
  const double mesh_seconds = seconds(t0);
  const std::vector<std::string> solvers =
      solver == "both" ? std::vector<std::string>{"dense", "hmatrix"} : std::vector<std::string>{solver};
  std::vector<Run> runs;
  for (const std::string& s : solvers) {
    const double cpu_before = cpu_seconds();
    runs.push_back(run(p, s, options));
    const double cpu = cpu_seconds() - cpu_before;
    const Run& r = runs.back();
    std::printf(
        "{\"shape\": \"%s\", \"faces\": %ld, \"solver\": \"%s\", \"h0\": %.6g, "
        "\"eta\": %.3g, \"leaf\": %ld, \"single_precision\": %s, "
        "\"times\": {\"mesh\": %.3f, \"assemble\": %.3f, \"solve\": %.3f, \"features\": %.3f}, "
        "\"iterations\": %d, \"residual\": %.3g, \"peak_rss_mb\": %.1f, \"operator_mb\": %.1f, "
        "\"compression\": %.4f, \"error\": %.3e, \"cpu_seconds\": %.1f, \"method\": \"%s\", "
        "\"gmres_restart\": %d",
        shape.c_str(), long(p.mesh.num_faces()), s.c_str(), p.h0, options.eta,
        long(options.leaf_size), options.single_precision ? "true" : "false", mesh_seconds,
        r.assemble, r.solve, r.features, r.solution.report.iterations, r.solution.report.residual,
        double(peak_resident_bytes()) / 1e6, double(r.solution.report.operator_bytes) / 1e6,
        r.solution.report.compression, r.error, cpu, r.solution.report.method.c_str(),
        r.solution.report.restart);
    // Stage timings as a JSON object of seconds; nothing for the dense path.
    const auto print_stages = [](const char* name,
                                 const std::vector<std::pair<std::string, double>>& stages) {
      if (stages.empty()) return;
      std::printf(", \"%s\": {", name);
      const char* separator = "";
      for (const auto& [stage, stage_seconds] : stages) {
        std::printf("%s\"%s\": %.3f", separator, stage.c_str(), stage_seconds);
        separator = ", ";
      }
      std::printf("}");
    };
    print_stages("assembly_stages", r.solution.report.assembly_stages);
    print_stages("solve_stages", r.solution.report.solve_stages);
    if (!r.solution.report.operator_parts.empty()) {
      std::printf(", \"operator_parts_mb\": {");
      const char* separator = "";
      for (const auto& [part, bytes] : r.solution.report.operator_parts) {
        std::printf("%s\"%s\": %.1f", separator, part.c_str(), double(bytes) / 1e6);
        separator = ", ";
      }
      std::printf("}");
    }
    if (runs.size() == 2)
      std::printf(", \"difference\": {\"phi\": %.3e, \"q\": %.3e, \"thickness\": %.3e}",
                  relative_difference(runs[0].solution.phi, runs[1].solution.phi),
                  relative_difference(runs[0].solution.q, runs[1].solution.q),
                  relative_difference(runs[0].thickness, runs[1].thickness));
    std::printf("}\n");
    std::fflush(stdout);
  }
  return 0;
}

int main(int argc, char** argv) {
  try {
    return benchmark(argc, argv);
  } catch (const std::exception& e) {  // the memory guard's ResourceError, a mesh file's InputError
    std::fprintf(stderr, "bench_fast_path: %s\n", e.what());
    return 2;
  }
}
