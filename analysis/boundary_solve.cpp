#include "analysis/boundary_solve.hpp"

#include <cmath>
#include <limits>
#include <new>
#include <string>

#include "analysis/memory_budget.hpp"
#include "bem/kernels/transmission_parameters.hpp"
#include "bem/solve/dense_transmission_solver.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/memory_watch.hpp"
#include "core/number_text.hpp"
#include "core/solver_memory_refusal.hpp"

namespace bemshape::analysis {

void validate(const SolveOptions& options) {
  bem::TransmissionParameters::from_shape(options.h0, options.a);  // throws for h0, a
  if (options.sharp_angle_degrees &&
      !(*options.sharp_angle_degrees >= 0.0 && *options.sharp_angle_degrees < 180.0))
    throw InputError("--sharp-angle must be in [0, 180) degrees, got " +
                     number_text(*options.sharp_angle_degrees, 3));
  if (options.max_edge && !(std::isfinite(*options.max_edge) && *options.max_edge > 0.0))
    throw InputError("--max-edge must be a positive length, got " +
                     number_text(*options.max_edge, 3));
  const std::optional<double>& tolerance = options.solver.tolerance;
  if (tolerance && !(*tolerance > 0.0 && *tolerance < 1.0))
    throw InputError("--tolerance must be in (0, 1), got " + number_text(*tolerance, 3));
}

geometry::GradedMeshParameters wall_reading_mesh_parameters(double h0, double a,
                                                            std::optional<double> sharp_angle_degrees) {
  geometry::GradedMeshParameters p;
  p.h0 = h0;
  p.fine_edge = bem::TransmissionParameters::from_shape(h0, a).default_max_edge();
  p.max_edge_ratio = kWallMeshMaxEdgeRatio;
  p.wall_thickness_ratio = kWallMeshThicknessRatio;
  p.thin_wall_ratio = kWallMeshThinWallRatio;
  p.gradation = kWallMeshGradation;
  p.refine_creases = false;
  p.min_size_ratio = kWallMeshMinSizeRatio;
  p.min_chord_ratio = 0.0;
  p.chord_thickness_ratio = kWallMeshChordRatio;
  p.crease_angle_degrees = sharp_angle_degrees.value_or(kWallMeshCreaseAngle);
  p.normal_scale_ratio = kWallMeshNormalScale;
  p.require_facet_strips = false;
  p.curve_turn_degrees = kWallMeshCurveTurn;
  return p;
}

namespace {

/// An edge --fit-memory tries is at least this much longer than the last one refused.
constexpr double kFitEdgeStep = 1.1;

/// No face limit on the dense path (--solver dense).
constexpr long kNoFaceLimit = std::numeric_limits<long>::max() - 1;

/// A closed surface has at least 4 triangles: a fitting mesh of fewer faces does not exist.
constexpr double kFewestSolverFaces = 4.0;

/// Remeshes `input` to run.max_edge (graded: the wall reading's mesh) and solves on it; with
/// `check_only`, stops after the solver's memory check and returns its estimate [bytes].
/// Throws SolverMemoryRefusal where the solver's estimate does not fit, before allocating.
std::uint64_t mesh_and_solve(const geometry::PreparedMesh& input, const SolveOptions& options,
                             const bem::TransmissionParameters& parameters, bool graded,
                             const geometry::GradedMeshParameters& graded_parameters,
                             BoundarySolve& run, const ProgressCallback& progress,
                             StageTimes& times, bool check_only) {
  const std::string& source = input.report.source;
  // Before remeshing: a solver mesh of about area/(0.43·edge²) faces (fewer than the
  // remesher makes) whose fast path cannot fit even at its smallest (preconditioner and
  // the shortest Krylov bases) is refused now rather than after minutes of remeshing.
  const double predicted_faces = input.mesh.area() / (0.43 * run.max_edge * run.max_edge);
  if (options.solver.method != SolverMethod::dense && predicted_faces > auto_dense_faces(graded)) {
    std::string reason;
    const std::uint64_t limit = resident_memory_limit_bytes(options.max_memory_bytes, &reason);
    const std::uint64_t least =
        process_memory().resident +
        bem::hmatrix_solver_minimum_bytes(Eigen::Index(predicted_faces), bem::HMatrixSolverOptions{});
    if (limit > 0 && least > limit)
      throw SolverMemoryRefusal(
          "the hierarchical-matrix BEM system of about " +
              std::to_string(std::llround(predicted_faces)) + " solver faces (edge " +
              number_text(run.max_edge, 3) + ", " + run.max_edge_rule + ") needs more than " +
              number_text(double(least) / 1e9, 3) + " GB but only " +
              number_text(double(limit) / 1e9, 3) + " GB may be used" + reason +
              "; use a coarser mesh (larger --max-edge)" +
              (reason == " (--max-memory)" ? " or a larger --max-memory" : ""),
          SolverMemoryRefusal::Solver::hmatrix, std::lround(predicted_faces), double(least),
          double(limit),
          double(process_memory().resident));
  }
  set_memory_context(source + ": remeshing to edge " + number_text(run.max_edge, 3) + " (" +
                         run.max_edge_rule + ")",
                     "use a coarser mesh (larger --max-edge) or a larger --max-memory");
  // Each stage is announced when it starts: the libraries report their first progress only
  // after some work, and a display ends the previous stage when a new name arrives.
  report_progress(progress, "remeshing", 0.0);
  run.solver_mesh = times.time("refine", [&] {
    if (graded) {
      geometry::GradedMesh mesh = geometry::graded_solver_mesh(input.mesh, graded_parameters, progress);
      run.graded = mesh.report;
      return std::move(mesh.mesh);
    }
    geometry::RemeshingOptions remeshing;
    remeshing.sharp_angle_degrees =
        options.sharp_angle_degrees.value_or(geometry::RemeshingOptions{}.sharp_angle_degrees);
    return geometry::refine_to_edge_length(input.mesh, run.max_edge, remeshing, progress);
  });

  const Eigen::Index faces = run.solver_mesh.num_faces();
  const SolverChoice& solver = options.solver;
  report_progress(progress, "assemble", 0.0);
  if (solver.method == SolverMethod::hmatrix ||
      (solver.method == SolverMethod::automatic && faces > auto_dense_faces(graded))) {
    bem::HMatrixSolverOptions hmatrix;
    const double tolerance = solver_tolerance(options);
    hmatrix.tolerance = tolerance;
    hmatrix.aca_tolerance = kCompressionToleranceRatio * tolerance;
    hmatrix.single_precision = tolerance >= bem::kSinglePrecisionStorageTolerance;
    hmatrix.max_memory_bytes = options.max_memory_bytes;
    hmatrix.far_field = solver.far_field;
    hmatrix.estimate_only = check_only;
    try {
      run.solution =
          bem::solve_transmission_hmatrix(run.solver_mesh, parameters, hmatrix, progress);
    } catch (const SolverMemoryRefusal&) {
      throw;  // its estimate was over the budget before assembly: solve_boundary names a mesh
    } catch (const ResourceError& refused) {
      // The solver's estimate was over the budget before assembly, or the memory watch
      // stopped the assembly: name the input too.
      throw ResourceError(source + ": " + refused.what());
    } catch (const std::bad_alloc&) {
      // An allocation failed before the watch saw the run outgrow its budget.
      throw ResourceError(source + ": the hierarchical-matrix BEM solver ran out of memory for " +
                          std::to_string(faces) + " solver faces (edge " +
                          number_text(run.max_edge, 3) +
                          "); use a coarser mesh (larger --max-edge) or a larger --max-memory");
    }
    return run.solution.report.memory_estimate_bytes;
  } else {
    // The refusal names a --max-edge that fits; flat walls stay accurate up to κ·h = 5.
    const DenseSystemRefusal refusal{source,
                                     faces,
                                     run.max_edge,
                                     run.max_edge_rule,
                                     2.5 * options.a * options.h0,
                                     options.max_memory_bytes};
    const std::uint64_t budget = memory_budget_bytes(options.max_memory_bytes);
    // The dense solver's own bound on the peak (what the process holds, the system, the
    // work per face), so that --fit-memory inverts the figure the refusal is made on.
    const double held = double(process_memory().resident);
    const double needed = double(bem::dense_solver_peak_bytes(faces, std::uint64_t(held)));
    if (budget > 0 && needed > double(budget))
      throw SolverMemoryRefusal(
          "the dense BEM solver needs " + number_text(needed / 1e9, 3) + " GB for " +
              std::to_string(faces) + " solver faces (edge " + number_text(run.max_edge, 3) +
              ", " + run.max_edge_rule + ") but only " + number_text(double(budget) / 1e9, 3) +
              " GB may be used" + memory_budget_reason(options.max_memory_bytes),
          SolverMemoryRefusal::Solver::dense, long(faces), needed, double(budget), held);
    if (check_only)
      return std::uint64_t(needed);
    bem::DenseSolverOptions dense;
    dense.max_memory_bytes = options.max_memory_bytes;
    try {
      run.solution = bem::solve_transmission_dense(run.solver_mesh, parameters, dense, progress);
    } catch (const ResourceError& stopped) {
      if (detail::memory_overrun.load())  // the memory watch stopped the assembly
        throw ResourceError(source + ": " + stopped.what());
      // The machine's free memory dropped between our check and the allocation: refused
      // as it stands (the message names the input and a --max-edge that fits).
      try {
        refuse_dense_system(refusal, memory_budget_bytes(options.max_memory_bytes));
      } catch (const SolverMemoryRefusal& refused) {
        throw ResourceError(refused.what());
      }
    }
    return run.solution.report.memory_estimate_bytes;
  }
}

}  // namespace

BoundarySolve solve_boundary(const geometry::PreparedMesh& input, const SolveOptions& options,
                             StageTimes& times, const ProgressCallback& progress) {
  validate(options);
  // The running account of the process's memory while it remeshes and solves: a run that
  // outgrows its budget stops at the next poll point with a ResourceError.
  const MemoryWatch watch(options.max_memory_bytes);
  const std::string& source = input.report.source;
  const auto parameters = bem::TransmissionParameters::from_shape(options.h0, options.a);
  BoundarySolve run;
  bool graded = !options.max_edge && options.mesh_rule == SolverMeshRule::wall_reading;
  const geometry::GradedMeshParameters graded_parameters =
      wall_reading_mesh_parameters(options.h0, options.a, options.sharp_angle_degrees);
  if (options.max_edge) {
    run.max_edge = *options.max_edge;
    run.max_edge_rule = "--max-edge";
  } else if (graded) {
    run.max_edge = graded_parameters.max_edge_ratio * options.h0;
    run.max_edge_rule = "graded for the wall reading: about the local wall, at most " +
                        number_text(graded_parameters.max_edge_ratio, 3) + "*h0";
  } else {
    run.max_edge = parameters.default_max_edge();
    run.max_edge_rule = "default rule 3/kappa = 1.5*a*h0";
  }
  // The solver mesh and its solve. Where the solver's estimate does not fit the budget
  // (SolverMemoryRefusal, before anything large is allocated), a uniform mesh is predicted
  // from that estimate and remeshed, and the solver's estimate on it decides (a longer edge
  // where it still does not fit): with fit_memory it is solved on, else the refusal names it.
  const double area = input.mesh.area();
  // The meshes tried to fit the budget are uniform.
  const long dense_up_to = options.solver.method == SolverMethod::dense     ? kNoFaceLimit
                           : options.solver.method == SolverMethod::hmatrix ? 0
                                                                            : auto_dense_faces(false);
  std::string first_refusal;  // the default mesh's refusal, what a refusal says first
  for (int attempt = 0;; ++attempt) {
    const bool check_only = attempt > 0 && !options.fit_memory;
    try {
      const std::uint64_t estimate = mesh_and_solve(input, options, parameters, graded,
                                                    graded_parameters, run, progress, times,
                                                    check_only);
      if (!check_only)
        break;
      throw ResourceError(source + ": " + first_refusal + "; a mesh that fits: --max-edge " +
                          number_text(run.max_edge, 3) + " (" +
                          std::to_string(run.solver_mesh.num_faces()) +
                          " solver faces, estimated peak " +
                          number_text(double(estimate) / 1e9, 3) + " GB; " +
                          fitting_mesh_accuracy(run.max_edge, options.h0, options.a) +
                          "), or --fit-memory to take it");
    } catch (const SolverMemoryRefusal& refused) {
      if (attempt == 0)
        first_refusal = refused.what();
      const double target = fitting_solver_faces(refused, dense_up_to);
      if (target < kFewestSolverFaces)
        throw ResourceError(source + ": " + first_refusal +
                            "; no coarser mesh fits: the process holds " +
                            number_text(refused.held_bytes / 1e9, 3) +
                            " GB already; use a larger --max-memory");
      if (attempt == kMemoryFitAttempts)
        throw ResourceError(source + ": " + first_refusal + "; no uniform mesh fitted in " +
                            std::to_string(kMemoryFitAttempts) + " tries, the last (edge " +
                            number_text(run.max_edge, 3) + ") " + refused.what());
      // A uniform mesh already made calibrates the prediction by the remesher's own count.
      const bool uniform = !run.graded && run.solver_mesh.num_faces() == refused.faces;
      double edge = uniform ? run.max_edge * std::sqrt(double(refused.faces) / target)
                            : uniform_mesh_edge_for_faces(area, target);
      if (uniform)
        edge = std::max(edge, kFitEdgeStep * run.max_edge);
      // The edge as the message prints it, so that the --max-edge named is the one checked.
      edge = fitting_edge_text_value(edge);
      if (options.fit_memory) {
        if (!run.memory_fit)
          run.memory_fit = MemoryFit{refused.faces, refused.needed_bytes, refused.budget_bytes, 0};
        ++run.memory_fit->attempts;
      }
      run.max_edge = edge;
      run.max_edge_rule = "uniform, predicted to fit the memory budget";
      run.graded.reset();
      graded = false;
      report_progress(progress,
                      "fitting the memory budget: --max-edge " + number_text(edge, 3) +
                          " (about " + std::to_string(std::lround(target)) + " solver faces)",
                      0.0);
    }
  }
  times.add("assemble", run.solution.report.assembly_seconds);
  times.add("solve", run.solution.report.solve_seconds);
  return run;
}

}  // namespace bemshape::analysis
