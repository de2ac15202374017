#pragma once
// The stages every job that solves shares, after the input mesh is read, validated and
// repaired (geometry/mesh_preparation.hpp): refine it to the solver's element size
// (geometry/isotropic_remeshing.hpp), choose the linear solver and solve the transmission
// problem for s_1, s_2, s_3 (bem/solve/dense_transmission_solver.hpp,
// bem/solve/hmatrix_transmission_solver.hpp).
//
// Element size: the solver mesh's edges are about `max_edge` (none longer than 1.3 times
// it, geometry::RemeshingOptions::max_edge_ratio) if given, else the default of what is read
// (SolverMeshRule): for values on the surface (the sphere and paper measures, the features at
// points) the uniform TransmissionParameters::default_max_edge() = 3/κ = 1.5·a·h0 [model
// units]; for the wall reading a graded mesh whose elements follow the walls
// (wall_reading_mesh_parameters, docs/theory.md "Element size").

#include <cstdint>
#include <optional>
#include <string>

#include "analysis/stage_times.hpp"
#include "bem/solve/boundary_solution.hpp"
#include "bem/solve/hmatrix_transmission_solver.hpp"
#include "core/progress.hpp"
#include "geometry/isotropic_remeshing.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

/// The linear solver of the transmission problem.
enum class SolverMethod {
  automatic,  ///< dense up to kAutoDenseFaces solver faces, the H-matrix path above
  dense,      ///< LU of the dense system (bem::solve_transmission_dense)
  hmatrix     ///< H-matrix and GMRES (bem::solve_transmission_hmatrix)
};

/// Which linear solver runs and how (the command line's --solver, --far-field, --tolerance).
struct SolverChoice {
  SolverMethod method = SolverMethod::automatic;
  /// Relative residual the iterative (H-matrix) path must reach, in (0, 1); empty: the
  /// default of what is read (solver_tolerance).
  std::optional<double> tolerance;
  /// How the H-matrix path keeps the Laplace far field: automatic (the H-matrix's own
  /// factors where they fit in memory, the H² form where not), hmatrix or nested (H²).
  bem::HMatrixSolverOptions::FarField far_field = bem::HMatrixSolverOptions::FarField::automatic;
};

/// The largest solver mesh SolverMethod::automatic gives to the dense path. Measured on the
/// ball (bench/bench_fast_path, docs/benchmarks.md): the two paths take the same time near
/// 1300 faces; the dense path's exact solve is kept a little beyond.
inline constexpr long kAutoDenseFaces = 2000;
/// ... and of the wall reading's graded mesh, whose elements span many 1/κ: there the dense
/// assembly's every pair costs more than the H-matrix path's compression saves from 800
/// faces on (CPU seconds of the whole run, dense against H-matrix, fine exports through
/// `bemshape thickness`: the taper at 498 solver faces 3.3 and 4.0, the bent bracket at
/// 1,086 5.5 and 4.4, the boss-tab part at 1,304 6.0 and 4.5, the plate-holes part at 2,122
/// 8.8 and 5.2).
inline constexpr long kAutoDenseGradedFaces = 800;
/// The face count up to which SolverMethod::automatic solves densely, for a graded
/// (wall-reading) or uniform mesh.
constexpr long auto_dense_faces(bool graded) { return graded ? kAutoDenseGradedFaces : kAutoDenseFaces; }

/// What the default solver mesh (no max_edge) is made for.
enum class SolverMeshRule {
  /// Values of s and ∇s on the surface (the sphere and paper measures, `features`, `compare`):
  /// uniform elements of 3/κ, the layer of width 1/κ outside the surface resolved.
  surface_values,
  /// The wall reading at the walls' mid-surfaces, half a wall deep: a graded mesh with
  /// elements about as long as the local wall (geometry::graded_solver_mesh with
  /// wall_reading_mesh_parameters), creases kept but not refined, tessellated round walls
  /// crossed.
  wall_reading
};

/// Elements of the wall-reading mesh are at most this many times the local wall thickness
/// (geometry::GradedMeshParameters::wall_thickness_ratio, c_t) on flat walls. Along the
/// part's edges they are smaller: a wall's two rim creases are a wall apart, and the crease
/// spacing rule asks for c_l = 1.5 times that (geometry/mesh_size_field.hpp), from which the
/// gradation lets them grow; so the elements follow the walls where the field varies along
/// the wall (near edges, holes, ribs), while away from them, where the edges' disturbance has
/// decayed like e^{−πd/t}, the field is that of a plate at any element size. The wall is read
/// half a wall deep. On the fine exports of bench/bench_thickness_tools, against c_t = 1.5:
/// the 356 mm tray 77,788 → 45,248 solver faces (83 → 48–49 s, 1.75 → 1.06 GB), median
/// 1.0001 → 1.0000; the 100×80×30 tray 7,746 → 4,220, plate-holes 3,888 → 3,626, the
/// L-bracket 2,712 → 2,360, the boss-tab part 2,188 → 1,898, the bent bracket 1,734 → 1,330;
/// every nominal median within 0.35 % of the design and p05 within 1.8 % (plate_holes
/// 0.9827), the thin features one region each on 99.8–100 % of their area. The noisy plate of
/// tests/analysis/test_thickness_scale.cpp reads within 1 % of its wall on 47.2 % of its area
/// (its own wall at scale h0 on 46.7 %), p05 0.973.
inline constexpr double kWallMeshThicknessRatio = 3.0;
/// Neighbouring elements of the wall-reading mesh differ in size by at most this factor
/// (geometry::GradedMeshParameters::gradation, g). A steeper gradation would let the sizes
/// asked at creases close together (a counterbore's rims 0.9 mm apart) and along rounded
/// edges grow back to the walls' sooner: plate_holes takes 7,648 and 6,648 solver faces at
/// 1.5 and 1.6 against 9,020 (bench/bench_thickness_tools plate_holes). But at 1.5 the
/// σ = 3 % copies of the T-junction and the L-bracket read a false thin region each, and at
/// 1.6 a pit of h0/4 is flagged (tests/analysis/test_thickness_scale.cpp): fewer vertices
/// average less of the noise and follow less of a small feature.
inline constexpr double kWallMeshGradation = geometry::kDefaultGradation;
/// ... and at most this many times h0 anywhere (h_max / h0). It binds only on walls thicker
/// than (this / c_t)·h0: a part checked at an h0 well below its walls (`--min-thickness 1`
/// on a 4 mm plate: 14,052 solver faces at 2, 5,978 at 4, median 4.0145 and 4.0000).
inline constexpr double kWallMeshMaxEdgeRatio = 4.0;
/// Walls thinner than this times h0 get the fine edge 1.5·a·h0 (GradedMeshParameters::
/// thin_wall_ratio): thin features well below h0; thicker walls take c_t times their
/// thickness. At 0.75 the ribs and tabs of the labelled parts (0.55–0.74·h0) took the fine
/// edge: the L-bracket 4,300 solver faces, the boss-tab part 3,410, the tray 10,482, the
/// 356 mm tray 267,408; at 0.5 they take 2,712, 2,188, 7,746 and 79,574 (c_t 1.5), with the thin
/// features still flagged on 99.8–100 % of their area as one region and the nominal walls'
/// medians within 0.1 % (bench/bench_thickness_tools).
inline constexpr double kWallMeshThinWallRatio = 0.5;

/// Tessellated round walls are smoothed (crossed by the elements) where a chord sags by at
/// most this fraction of the wall under it (geometry::GradedMeshParameters::
/// chord_thickness_ratio). The chords of the tube's two skins sag the same way and their
/// errors partly cancel in the wall: its median reads 1.0021, 1.0032 and 1.0059 of the
/// design at 1 %, 1.5 % and 2 % with c_t 1.5 (4,184, 2,952 and 2,264 solver faces).
inline constexpr double kWallMeshChordRatio = 0.015;
/// No element is asked to be smaller than this times h_f = 1.5·a·h0, whatever creases are
/// close (GradedMeshParameters::min_size_ratio). TODO-measured.
inline constexpr double kWallMeshMinSizeRatio = 0.5;

/// Creases and tessellations of the wall reading's mesh are found from the face normals
/// averaged over this times h0 with the part's edges kept (geometry/bilateral_normals.hpp):
/// a scanned or noisy surface's roughness, details far below h0, makes no crease.
inline constexpr double kWallMeshNormalScale = 0.5;
/// ... and an edge is a crease where those normals differ by more than this [degrees]: the
/// averaged normals of a noisy flat wall stay within about 2° of each other. TODO-measured.
inline constexpr double kWallMeshCreaseAngle = 5.0;

/// A crease turning by at most this at a vertex [degrees] is a round rim's tessellation, not
/// a corner (geometry::GradedMeshParameters::curve_turn_degrees): the rims of holes, tubes and
/// bosses take elements of the size field, not of their export's segments. A polygon of 24
/// segments turns by 15° per vertex. TODO-measured.
inline constexpr double kWallMeshCurveTurn = 15.0;

/// ε of the interior far field's cross approximation and of the exterior near field's cutoff
/// (bem::HMatrixSolverOptions::aca_tolerance: pairs farther than −ln ε/κ dropped), as a
/// multiple of the Krylov tolerance. Single-precision storage already perturbs a product by
/// about 4e−7, so compressing to 1e−8 bought nothing. On the 81,920-face sphere of
/// docs/validation.md, "Surface values on a large sphere" (kept as given), ε 1e−8 → 1e−6
/// took the assembly from 18.5 to 14.0 s and the exterior near field from 620 to 382 MB, and
/// moved h_f by at most 1.5e−5 of its value at any vertex; the labelled parts' readings in
/// bench/bench_thickness_tools did not change in their four digits.
inline constexpr double kCompressionToleranceRatio = 1.0;

/// The GMRES relative residual (--tolerance) where none is given, by what is read. Values of
/// s and ∇s on the surface and at points (the sphere and paper measures, `features`,
/// `compare`): 1e−6, about the relative error of φ and q. The wall reading takes the zero of
/// s half a wall deep, where an error δ of s relative to its scale moves the zero by about δ
/// of the wall; 1e−5 moves the readings by less than that: on the fine exports of
/// bench/bench_thickness_tools the medians, p05 and p95 of every labelled part, of
/// plate_holes and of the 356 mm tray did not change in their four digits (plate_holes
/// 12.6961 both, p95 12.7050 → 12.7048), the tray took 26 iterations → 21, its assembly
/// 13.0 → 11.3 s (the compression tolerance follows, kCompressionToleranceRatio) and its run
/// 24.1 → 20.0 s. At 1e−4 the readings move by up to 4e−4 of the wall (the tray's thickest
/// reading 10.3035 → 10.2997) for another 2.6 s there.
inline constexpr double kSurfaceValuesTolerance = 1e-6;
inline constexpr double kWallReadingTolerance = 1e-5;

/// Meshes --fit-memory tries after the refused one before it refuses too.
inline constexpr int kMemoryFitAttempts = 4;

/// The graded mesh of the wall reading for h0 and a (SolverMeshRule::wall_reading).
geometry::GradedMeshParameters wall_reading_mesh_parameters(double h0, double a,
                                                            std::optional<double> sharp_angle_degrees);

/// The PDE's parameters, the solver mesh and the solver: what every job that solves takes.
struct SolveOptions {
  double h0 = 0.0;                 ///< characteristic length [model units], > 0
  double a = 0.2;                  ///< dimensionless diffusion, > 0
  std::optional<double> max_edge;  ///< solver mesh edge [model units]; default rule if empty
  /// The default solver mesh when max_edge is empty.
  SolverMeshRule mesh_rule = SolverMeshRule::surface_values;
  /// Dihedral angle above which an edge is kept as a crease by the remesher [degrees], in
  /// [0, 180); empty: the rule's default (geometry::RemeshingOptions::sharp_angle_degrees
  /// for surface values and --max-edge, kWallMeshCreaseAngle for the wall reading's mesh).
  std::optional<double> sharp_angle_degrees;
  std::uint64_t max_memory_bytes = 0;  ///< memory the solve may use; 0 = what the machine has
  /// Where the solver on the default mesh (or max_edge) would not fit: solve on the uniform
  /// mesh predicted to fit instead of refusing (--fit-memory; BoundarySolve::memory_fit).
  bool fit_memory = false;
  SolverChoice solver;
};

/// The mesh --fit-memory took in place of one whose solver did not fit.
struct MemoryFit {
  long refused_faces = 0;         ///< solver faces of the mesh that did not fit
  double refused_bytes = 0.0;     ///< its solver's estimate [bytes]
  double budget_bytes = 0.0;      ///< what may be used [bytes]
  int attempts = 0;               ///< meshes refused before the one solved on
};

/// The GMRES relative residual of a solve: options.solver.tolerance if given, else
/// kWallReadingTolerance for SolverMeshRule::wall_reading and kSurfaceValuesTolerance for
/// surface values.
inline double solver_tolerance(const SolveOptions& options) {
  return options.solver.tolerance.value_or(options.mesh_rule == SolverMeshRule::wall_reading
                                               ? kWallReadingTolerance
                                               : kSurfaceValuesTolerance);
}

/// Throws InputError naming the first option out of its range (h0, a, sharp angle,
/// max edge, tolerance), before anything is read or computed.
void validate(const SolveOptions& options);

/// The solver mesh and the boundary data on it.
struct BoundarySolve {
  geometry::SurfaceMesh solver_mesh;  ///< refined mesh the BEM runs on
  double max_edge = 0.0;              ///< target edge used [model units]; the graded mesh's h_max
  std::string max_edge_rule;          ///< "--max-edge", "default rule 3/kappa = 1.5*a*h0" or the graded rule
  /// The graded mesh's report (SolverMeshRule::wall_reading without max_edge), else empty.
  std::optional<geometry::GradedMeshReport> graded;
  /// Set when SolveOptions::fit_memory replaced a mesh that did not fit.
  std::optional<MemoryFit> memory_fit;
  bem::BoundarySolution solution;     ///< φ, q: #F×3 on solver_mesh
};

/// Refines `input` and solves on it, timing the stages in `times` as "refine", "assemble"
/// and "solve". Validates `options` first. Throws InputError for unusable options and
/// ResourceError when the system does not fit in memory (analysis/memory_budget.hpp): where
/// the solver's estimate is over the budget, one line naming the input and a uniform
/// --max-edge whose mesh the solver's estimate accepts, with the accuracy to expect there;
/// with fit_memory that mesh is solved on instead (at most kMemoryFitAttempts meshes tried).
BoundarySolve solve_boundary(const geometry::PreparedMesh& input, const SolveOptions& options,
                             StageTimes& times, const ProgressCallback& progress = {});

}  // namespace bemshape::analysis
