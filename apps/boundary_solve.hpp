#pragma once
// The stages `bemshape thickness` and `bemshape features` share: read, validate and repair
// the input (geometry/mesh_preparation.hpp), refine it to the solver's element size
// (geometry/isotropic_remeshing.hpp) and solve the transmission problem for s_1, s_2, s_3
// (bem/solve/dense_transmission_solver.hpp).
//
// Element size: the solver mesh's edges are about `max_edge` (none longer than 1.3 times
// it, geometry::RemeshingOptions::max_edge_ratio) if the user gave it, else the default rule
// TransmissionParameters::default_max_edge() = 3/κ = 1.5·a·h0 [model units].

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "apps/stage_times.hpp"
#include "bem/solve/boundary_solution.hpp"
#include "core/progress.hpp"
#include "geometry/isotropic_remeshing.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::apps {

/// Which linear solver runs (--solver, --tolerance).
struct SolverChoice {
  /// "auto" (dense up to kAutoDenseFaces solver faces, the H-matrix path above), "dense" or
  /// "hmatrix".
  std::string method = "auto";
  /// Relative residual the iterative (H-matrix) path must reach.
  double tolerance = 1e-6;
  /// How the H-matrix path keeps the Laplace far field: "auto" (the H-matrix's own factors
  /// where they fit in memory, the H² form where not), "hmatrix" or "nested" (H²;
  /// bem::HMatrixSolverOptions::FarField).
  std::string far_field = "auto";
};

/// The largest solver mesh "auto" gives to the dense path. Measured on the ball
/// (bench/bench_fast_path, docs/benchmarks.md): the two paths take the same time near 1300
/// faces; the dense path's exact solve is kept a little beyond.
inline constexpr long kAutoDenseFaces = 2000;

struct BoundarySolveSetup {
  std::string input;               ///< mesh file
  double h0 = 0.0;                 ///< characteristic length [model units]
  double a = 0.2;                  ///< dimensionless diffusion
  std::optional<double> max_edge;  ///< --max-edge [model units]; default rule if empty
  /// --sharp-angle [degrees]: dihedral angle above which an edge is kept as a crease by the
  /// remesher (geometry::RemeshingOptions::sharp_angle_degrees).
  double sharp_angle_degrees = geometry::RemeshingOptions{}.sharp_angle_degrees;
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory; 0 = what the machine has
  SolverChoice solver;                 ///< --solver, --tolerance
  /// Called after reading, before refining and solving (e.g. to refuse an absurd request
  /// that depends on the part's size before the expensive stages). Returns the bytes it
  /// keeps allocated through the solve, which come off --max-memory for the BEM (when
  /// given). May be empty.
  std::function<std::uint64_t(const geometry::PreparedMesh&)> check_input;
};

struct BoundarySolveRun {
  geometry::PreparedMesh input;       ///< the validated, repaired input mesh and its report
  geometry::SurfaceMesh solver_mesh;  ///< refined mesh the BEM runs on
  double max_edge = 0.0;              ///< target edge used [model units]
  std::string max_edge_rule;          ///< "--max-edge" or "default 3/kappa = 1.5*a*h0"
  bem::BoundarySolution solution;
};

/// Runs the three stages, timing them in `times` as "read", "refine", "assemble" and
/// "solve". Throws InputError for unusable input or options and ResourceError (one line
/// naming --max-edge and a value that fits) when the dense system does not fit in memory.
BoundarySolveRun prepare_and_solve(const BoundarySolveSetup& setup, StageTimes& times,
                                   const ProgressCallback& progress);

}  // namespace bemshape::apps
