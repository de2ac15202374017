#pragma once
// The local wall thickness of a solid part on its surface, and the minimum-wall-thickness
// check: the whole of `bemshape thickness` but reading options and writing files, in one
// call.
//
//   input mesh (validated, repaired: geometry/mesh_preparation.hpp)
//     → solver mesh and boundary solution (analysis/boundary_solve.hpp)
//     → features per face and vertex of the solver mesh (analysis/surface_features.hpp)
//     → the selected thickness per solver face: the wall thickness read at the mid-surface
//       (wall, analysis/wall_thickness.hpp), h_p (principal) or h_f (paper)
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

#include "analysis/area_histogram.hpp"
#include "analysis/boundary_solve.hpp"
#include "analysis/stage_times.hpp"
#include "analysis/surface_features.hpp"
#include "analysis/thickness_statistics.hpp"
#include "analysis/wall_thickness.hpp"
#include "core/progress.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::analysis {

/// Which thickness the statistics and the check use.
enum class ThicknessMeasure {
  wall,       ///< the thickness of the wall a face belongs to, read at its mid-surface
  principal,  ///< h_p at the surface point itself (an inscribed sphere's diameter there)
  paper       ///< h_f = h0(1/f_h − a), Yamada's f_h-based thickness
};

/// "wall", "principal" (alias "sphere") or "paper"; throws InputError naming the choices.
ThicknessMeasure thickness_measure(const std::string& name);

/// How edges and corners read under the wall measure (docs/theory.md, "Edges").
enum class EdgeMode {
  wall,  ///< every point reads the thickness of its wall, edges and corners included
  exact  ///< the smaller of the wall and of h_p at the point: convex edges and corners, where
         ///< the inscribed sphere at the point shrinks, read thinner (zero-radius edges: → 0)
};

/// "wall" or "exact"; throws InputError naming the choices.
EdgeMode edge_mode(const std::string& name);

/// Bins of the thickness's area histogram at most.
inline constexpr int kHistogramBins = 12;

struct ThicknessOptions {
  SolveOptions solve;  ///< h0, a, solver mesh, solver, memory
  /// Replace solve.h0 by the part's own length 2·volume/area (part_h0): the wall thickness
  /// of a plate exactly and of any thin-walled part nearly (ThicknessResult::h0_rule says so).
  bool h0_from_part = false;
  ThicknessMeasure measure = ThicknessMeasure::wall;
  EdgeMode edges = EdgeMode::wall;  ///< measure wall only
  /// The check's threshold [model units], > 0: every edge-connected set of solver faces
  /// thinner than it is a thin region. Empty: no check.
  std::optional<double> min_thickness;
  /// Thick regions [model units], > 0: every edge-connected set of measurable solver faces
  /// thicker than it is a thick region. Empty: none.
  std::optional<double> max_thickness;
  /// The speck area [model units²]: thin regions smaller than it are set aside from the list
  /// as specks (the verdict still counts them: ThinCheck), thick regions smaller than it are
  /// dropped; 0 keeps all. Empty: kSpeckArea·h0². Never more than kSpeckPartFraction of the
  /// part's area (speck_area).
  std::optional<double> min_region_area;
  /// With min_thickness: when no face is measurable at h0 the check fails
  /// (ThinCheck::unmeasurable) instead of the run refusing with an InputError. The front ends
  /// set it when the units check finds h0 or the limit implausible for the part (the lengths
  /// were meant in another unit, and a part read in the wrong unit must not come out of a
  /// check without a FAIL: docs/usage.md, "Units check"). The statistics are then NaN with
  /// every face's area unmeasurable.
  bool unmeasurable_fails_check = false;
  /// Also carry the features over to the input mesh (ThicknessResult::input_features;
  /// costs closest-point queries of both meshes).
  bool map_to_input = true;
};

/// 2·V/A of a closed surface [model units]: t for a plate of thickness t (up to its rims),
/// t/(1 + t/(2R)) ≈ t for a tube or shell wall of mid-radius R. Throws InputError if the
/// volume is not positive.
double part_h0(const geometry::MeshReport& report);

/// Throws InputError for options out of range (min_thickness, then validate(solve)).
void validate(const ThicknessOptions& options);

struct ThicknessResult {
  geometry::PreparedMesh input;     ///< the validated, repaired input and its report
  double h0 = 0.0;                  ///< the h0 used [model units]
  std::string h0_rule;              ///< "--h0" or "2*volume/area of the part"
  BoundarySolve boundary;           ///< solver mesh, max edge and its rule, φ and q
  SurfaceFeatures solver_features;  ///< on boundary.solver_mesh (kFeatureColumns)
  SurfaceFeatures input_features;   ///< on input.mesh; empty unless map_to_input
  int column = kColumnWall;         ///< column of the selected measure: kColumnWall, Hp or Hf
  std::string measure_column;       ///< "wall", "h_p" or "h_f"
  /// The mid-surface search per solver face (measure wall only; empty otherwise).
  WallThickness wall;
  Eigen::VectorXd thickness;        ///< #F of the solver mesh: the selected measure per face
  ThicknessStatistics statistics;   ///< of `thickness` over the solver faces
  std::vector<ThinRegion> regions;  ///< below min_thickness, most severe first, specks aside
  ThinCheck check;                  ///< the verdict and the specks (min_thickness only)
  std::vector<ThickRegion> thick_regions;  ///< above max_thickness, thickest first
  double min_region_area = 0.0;     ///< the speck area used (speck_area)
  AreaHistogram histogram;          ///< area per thickness range, at most kHistogramBins
  /// defect_faces[f] = 1 for the solver faces within h0 of a region where the input crosses
  /// itself and was measured as given (input.report.defects, geometry::faces_near_defects);
  /// all 0 when there is none.
  std::vector<char> defect_faces;
  /// Solver faces whose thickness h0(1/f − a) came out negative and was clamped to 0
  /// (features/thickness.hpp): f above 1/a, which only discretisation error produces.
  Eigen::Index clamped_faces = 0;
  /// Wall time of the stages: "read" (file input only), "refine", "assemble", "solve",
  /// "features", "mid-surface search" and "pairing" (measure wall only), "regions"
  /// (statistics, regions, histogram), "map_back" (map_to_input only).
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
