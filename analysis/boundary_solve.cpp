#include "analysis/boundary_solve.hpp"

#include <cmath>
#include <new>
#include <string>

#include "analysis/memory_budget.hpp"
#include "bem/kernels/transmission_parameters.hpp"
#include "bem/solve/dense_transmission_solver.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/memory_watch.hpp"
#include "core/number_text.hpp"

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
  if (!(options.solver.tolerance > 0.0 && options.solver.tolerance < 1.0))
    throw InputError("--tolerance must be in (0, 1), got " +
                     number_text(options.solver.tolerance, 3));
}

geometry::GradedMeshParameters wall_reading_mesh_parameters(double h0, double a,
                                                            std::optional<double> sharp_angle_degrees) {
  geometry::GradedMeshParameters p;
  p.h0 = h0;
  p.fine_edge = bem::TransmissionParameters::from_shape(h0, a).default_max_edge();
  p.max_edge_ratio = kWallMeshMaxEdgeRatio;
  p.wall_thickness_ratio = kWallMeshThicknessRatio;
  p.thin_wall_ratio = kWallMeshThinWallRatio;
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

BoundarySolve solve_boundary(const geometry::PreparedMesh& input, const SolveOptions& options,
                             StageTimes& times, const ProgressCallback& progress) {
  validate(options);
  // The running account of the process's memory while it remeshes and solves: a run that
  // outgrows its budget stops at the next poll point with a ResourceError.
  const MemoryWatch watch(options.max_memory_bytes);
  const std::string& source = input.report.source;
  const auto parameters = bem::TransmissionParameters::from_shape(options.h0, options.a);
  BoundarySolve run;
  const bool graded = !options.max_edge && options.mesh_rule == SolverMeshRule::wall_reading;
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
  // Before remeshing: a solver mesh of about area/(0.43·edge²) faces (fewer than the
  // remesher makes) whose fast path cannot fit even at its smallest (preconditioner and
  // the shortest Krylov bases) is refused now rather than after minutes of remeshing.
  const double predicted_faces = input.mesh.area() / (0.43 * run.max_edge * run.max_edge);
  if (options.solver.method != SolverMethod::dense && predicted_faces > kAutoDenseFaces) {
    std::string reason;
    const std::uint64_t limit = resident_memory_limit_bytes(options.max_memory_bytes, &reason);
    const std::uint64_t least =
        process_memory().resident +
        bem::hmatrix_solver_minimum_bytes(Eigen::Index(predicted_faces), bem::HMatrixSolverOptions{});
    if (limit > 0 && least > limit)
      throw ResourceError(
          source + ": the hierarchical-matrix BEM system of about " +
          std::to_string(std::llround(predicted_faces)) + " solver faces (edge " +
          number_text(run.max_edge, 3) + ", " + run.max_edge_rule + ") needs more than " +
          number_text(double(least) / 1e9, 3) + " GB but only " +
          number_text(double(limit) / 1e9, 3) + " GB may be used" + reason +
          "; use a coarser mesh (larger --max-edge)" +
          (reason == " (--max-memory)" ? " or a larger --max-memory" : ""));
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
      (solver.method == SolverMethod::automatic && faces > kAutoDenseFaces)) {
    bem::HMatrixSolverOptions hmatrix;
    hmatrix.tolerance = solver.tolerance;
    // ε two digits below the Krylov tolerance (bem/solve/hmatrix_transmission_solver.hpp).
    hmatrix.aca_tolerance = 1e-2 * solver.tolerance;
    // A single-precision H-matrix perturbs a product by about 4e−7: fine for a residual of
    // 1e−6, not for a tighter one.
    hmatrix.single_precision = solver.tolerance >= 1e-6;
    hmatrix.max_memory_bytes = options.max_memory_bytes;
    hmatrix.far_field = solver.far_field;
    try {
      run.solution =
          bem::solve_transmission_hmatrix(run.solver_mesh, parameters, hmatrix, progress);
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
  } else {
    // The refusal names a --max-edge that fits; flat walls stay accurate up to κ·h = 5.
    const DenseSystemRefusal refusal{source,
                                     faces,
                                     run.max_edge,
                                     run.max_edge_rule,
                                     2.5 * options.a * options.h0,
                                     options.max_memory_bytes};
    require_dense_system_fits(refusal);
    bem::DenseSolverOptions dense;
    dense.max_memory_bytes = options.max_memory_bytes;
    try {
      run.solution = bem::solve_transmission_dense(run.solver_mesh, parameters, dense, progress);
    } catch (const ResourceError& stopped) {
      if (detail::memory_overrun.load())  // the memory watch stopped the assembly
        throw ResourceError(source + ": " + stopped.what());
      // The machine's free memory dropped between our check and the allocation.
      refuse_dense_system(refusal, memory_budget_bytes(options.max_memory_bytes));
    }
  }
  times.add("assemble", run.solution.report.assembly_seconds);
  times.add("solve", run.solution.report.solve_seconds);
  return run;
}

}  // namespace bemshape::analysis
