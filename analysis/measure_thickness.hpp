#pragma once
// The local wall thickness of a solid part on its surface, and the minimum-wall-thickness
// check: the whole of `bemshape thickness` but reading options and writing files, in one
// call.
//
//   input mesh (validated, repaired: geometry/mesh_preparation.hpp)
//     → solver mesh and boundary solution (analysis/boundary_solve.hpp)
//     → features per face and vertex of the solver mesh (analysis/surface_features.hpp)
//     → the selected thickness per solver face: h_p (principal) or h_f (paper)
//     → area-weighted statistics and thin regions on the solver faces
//       (analysis/thickness_statistics.hpp)
//     → optionally the features carried back to the input mesh's vertices and faces.
//
// Lengths are in the input's units; the thickness saturates at kMaxThicknessFactor·h0
// (features/thickness.hpp) where no opposite wall is within the PDE's reach, and such faces
// are left out of the statistics (ThicknessStatistics::unmeasurable_area).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/boundary_solve.hpp"
#include "analysis/stage_times.hpp"
#include "analysis/surface_features.hpp"
#include "analysis/thickness_statistics.hpp"
#include "core/progress.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::analysis {

/// Which thickness the statistics and the check use.
enum class ThicknessMeasure {
  principal,  ///< h_p, across the wall (inscribed-sphere diameter, the CAD meaning)
  paper       ///< h_f = h0(1/f_h − a), Yamada's f_h-based thickness
};

struct ThicknessOptions {
  SolveOptions solve;  ///< h0, a, solver mesh, solver, memory
  ThicknessMeasure measure = ThicknessMeasure::principal;
  /// The check's threshold [model units], > 0: every edge-connected set of solver faces
  /// thinner than it is a thin region. Empty: no check.
  std::optional<double> min_thickness;
  /// Also carry the features over to the input mesh (ThicknessResult::input_features;
  /// costs closest-point queries of both meshes).
  bool map_to_input = true;
};

/// Throws InputError for options out of range (min_thickness, then validate(solve)).
void validate(const ThicknessOptions& options);

struct ThicknessResult {
  geometry::PreparedMesh input;     ///< the validated, repaired input and its report
  BoundarySolve boundary;           ///< solver mesh, max edge and its rule, φ and q
  SurfaceFeatures solver_features;  ///< on boundary.solver_mesh (kFeatureColumns)
  SurfaceFeatures input_features;   ///< on input.mesh; empty unless map_to_input
  int column = kColumnHp;           ///< column of the selected measure: kColumnHp or kColumnHf
  std::string measure_column;       ///< "h_p" or "h_f"
  Eigen::VectorXd thickness;        ///< #F of the solver mesh: the selected measure per face
  ThicknessStatistics statistics;   ///< of `thickness` over the solver faces
  std::vector<ThinRegion> regions;  ///< below min_thickness, most severe first
  /// Solver faces whose thickness h0(1/f − a) came out negative and was clamped to 0
  /// (features/thickness.hpp): f above 1/a, which only discretisation error produces.
  Eigen::Index clamped_faces = 0;
  /// Wall time of the stages: "read" (file input only), "refine", "assemble", "solve",
  /// "features", "map_back" (map_to_input only).
  StageTimes times;
};

/// The thickness of the solid bounded by `input` (as geometry::prepare_mesh_file, or
/// prepare_triangles for arrays, return it). Throws InputError for unusable options or when
/// no face is measurable, ResourceError when the solve does not fit in memory,
/// NumericalError when it fails, CancelledError when the run is cancelled
/// (core/cancellation.hpp).
ThicknessResult measure_thickness(const geometry::PreparedMesh& input,
                                  const ThicknessOptions& options,
                                  const ProgressCallback& progress = {});

/// The same for a mesh file (.stl, .obj, .off, .ply, .3mf), read, validated and repaired first
/// (stage "read"); throws InputError for a file that cannot be used.
ThicknessResult measure_thickness(const std::filesystem::path& file,
                                  const ThicknessOptions& options,
                                  const ProgressCallback& progress = {});

}  // namespace bemshape::analysis
