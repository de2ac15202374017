#include "apps/boundary_solve.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <cstdio>
#include <sstream>

#include "apps/report_text.hpp"
#include "bem/solve/dense_transmission_solver.hpp"
#include "bem/solve/hmatrix_transmission_solver.hpp"
#include "bem/kernels/transmission_parameters.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "geometry/isotropic_remeshing.hpp"

namespace bemshape::apps {
namespace {

/// Memory the dense path may use: --max-memory if given, capped by what the machine and
/// `ulimit -v` allow (core/memory.hpp's budget, the one require_memory applies).
std::uint64_t dense_budget_bytes(std::uint64_t max_memory_bytes) {
  return memory_budget_bytes(max_memory_bytes);
}

/// The one-line refusal when the dense matrix does not fit: how many faces, how much memory,
/// and a --max-edge that fits. Face count scales like 1/edge², memory like faces².
[[noreturn]] void throw_does_not_fit(const BoundarySolveSetup& setup, const BoundarySolveRun& run,
                                     std::uint64_t budget) {
  const auto faces = static_cast<double>(run.solver_mesh.num_faces());
  const double needed = double(bem::dense_solver_memory_bytes(run.solver_mesh.num_faces()));
  // 10 % below the limit: the remesher's face count for a given edge varies by a few percent.
  const double fitting_faces = 0.9 * faces * std::sqrt(double(budget) / needed);
  const double edge = run.max_edge * std::sqrt(faces / std::max(fitting_faces, 1.0));
  std::ostringstream msg;
  msg << setup.input << ": the dense BEM solver needs " << number_text(needed / 1e9, 3)
      << " GB for " << run.solver_mesh.num_faces() << " solver faces (edge "
      << number_text(run.max_edge, 3) << ", " << run.max_edge_rule << ") but only "
      << number_text(double(budget) / 1e9, 3) << " GB may be used"
      << memory_budget_reason(setup.max_memory_bytes) << "; use a coarser mesh, e.g. "
      << "--max-edge " << number_text(edge, 3) << " (about " << std::lround(fitting_faces)
      << " faces; flat walls stay accurate up to --max-edge "
      << number_text(2.5 * setup.a * setup.h0, 3) << ")";
  throw ResourceError(msg.str());
}

}  // namespace

BoundarySolveRun prepare_and_solve(const BoundarySolveSetup& given, StageTimes& times,
                                   const ProgressCallback& progress) {
  BoundarySolveSetup setup = given;  // its --max-memory shrinks by what check_input holds
  const auto parameters = bem::TransmissionParameters::from_shape(setup.h0, setup.a);
  if (!(setup.sharp_angle_degrees >= 0.0 && setup.sharp_angle_degrees < 180.0))
    throw InputError("--sharp-angle must be in [0, 180) degrees, got " +
                     number_text(setup.sharp_angle_degrees, 3));
  if (setup.max_edge && !(std::isfinite(*setup.max_edge) && *setup.max_edge > 0.0))
    throw InputError("--max-edge must be a positive length, got " +
                     number_text(*setup.max_edge, 3));

  BoundarySolveRun run;
  run.input =
      times.time("read", [&] { return geometry::prepare_mesh_file(setup.input, {}, progress); });
  if (setup.check_input) {
    const std::uint64_t held = setup.check_input(run.input);
    if (setup.max_memory_bytes > 0)
      setup.max_memory_bytes = setup.max_memory_bytes > held ? setup.max_memory_bytes - held : 1;
  }
  if (setup.max_edge) {
    run.max_edge = *setup.max_edge;
    run.max_edge_rule = "--max-edge";
  } else {
    run.max_edge = parameters.default_max_edge();
    run.max_edge_rule = "default rule 3/kappa = 1.5*a*h0";
  }
  // Each stage is announced when it starts: the libraries report their first progress only
  // after some work, and the display ends the previous stage when a new name arrives.
  report_progress(progress, "remeshing", 0.0);
  run.solver_mesh = times.time("refine", [&] {
    geometry::RemeshingOptions remeshing;
    remeshing.sharp_angle_degrees = setup.sharp_angle_degrees;
    return geometry::refine_to_edge_length(run.input.mesh, run.max_edge, remeshing, progress);
  });

  const Eigen::Index faces = run.solver_mesh.num_faces();
  const std::string& method = setup.solver.method;
  if (method != "auto" && method != "dense" && method != "hmatrix")
    throw InputError("--solver must be auto, dense or hmatrix, got '" + method + "'");
  const std::string& far_field = setup.solver.far_field;
  if (far_field != "auto" && far_field != "hmatrix" && far_field != "nested")
    throw InputError("--far-field must be auto, hmatrix or nested, got '" + far_field + "'");
  if (!(setup.solver.tolerance > 0.0 && setup.solver.tolerance < 1.0))
    throw InputError("--tolerance must be in (0, 1), got " + number_text(setup.solver.tolerance, 3));
  report_progress(progress, "assemble", 0.0);
  if (method == "hmatrix" || (method == "auto" && faces > kAutoDenseFaces)) {
    bem::HMatrixSolverOptions options;
    options.tolerance = setup.solver.tolerance;
    // ε two digits below the Krylov tolerance (bem/solve/hmatrix_transmission_solver.hpp).
    options.aca_tolerance = 1e-2 * setup.solver.tolerance;
    // A single-precision H-matrix perturbs a product by about 4e−7: fine for a residual of
    // 1e−6, not for a tighter one.
    options.single_precision = setup.solver.tolerance >= 1e-6;
    options.max_memory_bytes = setup.max_memory_bytes;
    using FarField = bem::HMatrixSolverOptions::FarField;
    options.far_field = far_field == "hmatrix"  ? FarField::hmatrix
                        : far_field == "nested" ? FarField::nested
                                                : FarField::automatic;
    try {
      run.solution = bem::solve_transmission_hmatrix(run.solver_mesh, parameters, options, progress);
    } catch (const ResourceError& refused) {
      // The solver's estimate was over the budget before assembly: name the input too.
      throw ResourceError(setup.input + ": " + refused.what());
    } catch (const std::bad_alloc&) {
      // The estimate checked before assembly was low for this part (ranks, near field).
      throw ResourceError(setup.input + ": the hierarchical-matrix BEM solver ran out of memory for " +
                          std::to_string(faces) + " solver faces (edge " +
                          number_text(run.max_edge, 3) + "); use a coarser mesh (larger --max-edge)");
    }
  } else {
    const std::uint64_t budget = dense_budget_bytes(setup.max_memory_bytes);
    if (budget > 0 && bem::dense_solver_memory_bytes(faces) > budget)
      throw_does_not_fit(setup, run, budget);
    bem::DenseSolverOptions options;
    options.max_memory_bytes = setup.max_memory_bytes;
    try {
      run.solution = bem::solve_transmission_dense(run.solver_mesh, parameters, options, progress);
    } catch (const ResourceError&) {
      // The machine's free memory dropped between our check and the allocation.
      throw_does_not_fit(setup, run, dense_budget_bytes(setup.max_memory_bytes));
    }
  }
  times.add("assemble", run.solution.report.assembly_seconds);
  times.add("solve", run.solution.report.solve_seconds);
  return run;
}

}  // namespace bemshape::apps
