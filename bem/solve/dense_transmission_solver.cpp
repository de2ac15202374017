#include "bem/solve/dense_transmission_solver.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>

#include "linalg/blocked_lu.hpp"
#include "bem/operators/galerkin_operators.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/memory_watch.hpp"

namespace bemshape::bem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Relative residual above which a direct solve is reported as failed. Partial-pivot LU is
/// backward stable, so a healthy solve lands near machine precision times the growth
/// factor; 1e-6 only trips on a (numerically) singular system.
constexpr double kMaxDirectResidual = 1e-6;

/// Memory of the dense path beside the system per face [bytes]: the panels, both
/// operators' tables of touching pairs and the rows' thread-local work arrays, and the
/// margin over the system's own bytes (kDenseSystemMargin) for the heap's rounding of the
/// two matrices. Measured on a 3920-face ball (docs/reliability.md, "Estimate and peak"):
/// peak 1012 MB, of which 983 MB are the system and its copy.
constexpr double kDenseWorkBytesPerFace = 8000.0;
constexpr double kDenseSystemMargin = 1.05;

}  // namespace

std::uint64_t dense_solver_memory_bytes(Eigen::Index faces) {
  const auto n = static_cast<std::uint64_t>(2 * faces);
  // The matrix, overwritten in place by its LU factors, plus a copy kept for the residual.
  return 2 * n * n * sizeof(double);
}

std::uint64_t dense_solver_peak_bytes(Eigen::Index faces, std::uint64_t held_bytes) {
  return held_bytes + std::uint64_t(kDenseSystemMargin * double(dense_solver_memory_bytes(faces)) +
                                    kDenseWorkBytesPerFace * double(faces));
}

BoundarySolution solve_transmission_dense(const geometry::SurfaceMesh& mesh,
                                          const TransmissionParameters& parameters,
                                          const DenseSolverOptions& options,
                                          const ProgressCallback& progress) {
  const Eigen::Index n = mesh.num_faces();
  if (n == 0) throw InputError("the mesh has no faces");
  {
    std::ostringstream instead;
    instead << "the dense solver holds a " << 2 * n << "×" << 2 * n
            << " matrix; use a coarser mesh (larger --max-edge) or the hierarchical-matrix solver";
    require_memory(dense_solver_memory_bytes(n), "the dense BEM system", instead.str(),
                   options.max_memory_bytes);
  }
  // The bound on the process's peak: what it holds, the system, the tables of touching
  // pairs and the rows' work arrays (kDenseWorkBytesPerFace).
  const std::uint64_t estimate = dense_solver_peak_bytes(n, process_memory().resident);
  set_memory_context("the dense BEM system of " + std::to_string(n) + " faces",
                     "use a coarser mesh (larger --max-edge), the hierarchical-matrix solver "
                     "(--solver hmatrix) or a larger --max-memory");

  const auto start = Clock::now();
  const std::vector<Panel> panels = make_panels(mesh);
  GalerkinOperators<LaplaceKernel> laplace(LaplaceKernel{}, panels);
  GalerkinOperators<YukawaKernel> yukawa(YukawaKernel{parameters.kappa}, panels);
  laplace.tabulate_touching_pairs();
  yukawa.tabulate_touching_pairs();
  // Jump of the normal derivative, g_i = n_i/ã, per face (P0).
  const Eigen::MatrixX3d jump = mesh.face_normals() / parameters.a_tilde;

  // Every face, the columns of each row's exterior entries (GalerkinOperators::fill_row).
  std::vector<Eigen::Index> columns(static_cast<size_t>(n));
  std::iota(columns.begin(), columns.end(), Eigen::Index{0});
  Eigen::MatrixXd a(2 * n, 2 * n);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(2 * n, 3);
  std::atomic<Eigen::Index> rows_done{0};
#pragma omp parallel for schedule(dynamic, 8)
  for (Eigen::Index j = 0; j < n; ++j) {
    // A cancelled run skips the remaining rows (an exception cannot leave the parallel loop).
    if (cancellation_requested()) continue;
    // ½·M with M the P0 mass matrix diag(|T_j|).
    const double half_mass = 0.5 * mesh.face_areas()(j);
    Eigen::RowVector3d yukawa_of_jump = Eigen::RowVector3d::Zero();
    thread_local Eigen::MatrixXd laplace_v, laplace_k;
    laplace_v.resize(1, n);
    laplace_k.resize(1, n);
    laplace.fill_range(j, j + 1, 0, n, laplace_v, laplace_k);
    thread_local std::vector<GalerkinOperators<YukawaKernel>::Entry> yukawa_row;
    yukawa_row.resize(size_t(n));
    yukawa.fill_row(j, columns, yukawa_row);
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto& y = yukawa_row[size_t(k)];
      const double half = j == k ? half_mass : 0.0;
      a(j, k) = -(half + laplace_k(0, k));
      a(j, n + k) = laplace_v(0, k);
      a(n + j, k) = half - y.double_layer;
      a(n + j, n + k) = y.single_layer;
      yukawa_of_jump += y.single_layer * jump.row(k);
    }
    b.row(n + j) = yukawa_of_jump;
    const Eigen::Index done = ++rows_done;
    if (progress && done % 64 == 0) {
#pragma omp critical(bemshape_progress)
      report_progress(progress, "assemble", double(done) / double(n));
    }
  }
  throw_if_cancelled();
  report_progress(progress, "assemble", 1.0);
  BoundarySolution solution;
  solution.parameters = parameters;
  solution.report.method = "dense-lu";  // P0 Galerkin, partial-pivot LU
  solution.report.memory_estimate_bytes = estimate;
  solution.report.unknowns = 2 * n;
  solution.report.assembly_seconds = seconds_since(start);

  const auto solve_start = Clock::now();
  // Factorised as a copy: `a` is kept for the residual check.
  const linalg::LuFactors lu = linalg::lu_factorise(a, progress);
  const Eigen::MatrixXd z = linalg::lu_solve(lu, b);
  if (!z.allFinite())
    throw NumericalError("dense BEM solve: the solution contains NaN or Inf (singular system; "
                         "check the mesh for duplicate or degenerate faces)");
  double residual = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double norm_b = b.col(i).norm();
    if (norm_b > 0.0) residual = std::max(residual, (a * z.col(i) - b.col(i)).norm() / norm_b);
  }
  solution.report.residual = solution.report.preconditioned_residual = residual;
  solution.report.solve_seconds = seconds_since(solve_start);
  if (!(residual <= kMaxDirectResidual)) {
    std::ostringstream msg;
    msg << "dense BEM solve: relative residual " << residual << " exceeds " << kMaxDirectResidual
        << " (the system is numerically singular)";
    throw NumericalError(msg.str());
  }
  solution.phi = z.topRows(n);
  solution.q = z.bottomRows(n);
  return solution;
}

}  // namespace bemshape::bem
