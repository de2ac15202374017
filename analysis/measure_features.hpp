#pragma once
// The shape features inside a solid at given points or on a regular grid over its bounding
// box, by the boundary integral representation (bem/evaluate/potential_evaluation.hpp): no
// volume mesh. The whole of `bemshape features` but reading options and writing files.
//
//   input mesh → solver mesh and boundary solution (analysis/boundary_solve.hpp)
//     → s and ∇s at the points (treecode at the solver's tolerance), the inside flags
//       from the winding number → features::compute_features<3> at every point.

#include <array>
#include <filesystem>
#include <optional>

#include <Eigen/Core>

#include "analysis/boundary_solve.hpp"
#include "analysis/stage_times.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "core/progress.hpp"
#include "features/feature_parameters.hpp"
#include "features/point_features.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

/// Largest number of evaluation points accepted on a grid (and by `bemshape features` from
/// a file). The treecode of bem::evaluate_potential costs about 1.2 ms of CPU per point on a
/// 20,000-face part (docs/benchmarks.md, "Interior evaluation at many points"): 10⁶ points are
/// about ten minutes on two free cores — beyond that a coarser grid answers sooner.
inline constexpr double kMaxPoints = 1.0e6;

/// Nodes origin + (i, j, k)·spacing, i = 0 … cells[0] etc. [model units].
struct PointGrid {
  std::array<long long, 3> cells{};
  std::array<double, 3> origin{}, spacing{};

  double node_count() const {
    return double(cells[0] + 1) * double(cells[1] + 1) * double(cells[2] + 1);
  }
  /// The nodes, x fastest, then y, then z (VTK point order): #nodes×3.
  Eigen::MatrixX3d nodes() const;
};

/// The node grid of spacing h over `box`: symmetric about the box centre and covering it with
/// at most one spacing to spare on each side.
PointGrid grid_over(const geometry::BoundingBox& box, double spacing);

struct FeaturesOptions {
  SolveOptions solve;  ///< h0, a, solver mesh, solver, memory
  /// Half-width of the skeleton band [model units], ≥ 0 (features::FeatureParameters);
  /// default: the grid spacing on a grid, the solver mesh's max edge at points.
  std::optional<double> skeleton_width;
};

/// Throws InputError for options out of range (skeleton_width, then validate(solve)).
void validate(const FeaturesOptions& options);

struct FeaturesResult {
  geometry::PreparedMesh input;            ///< the validated, repaired input and its report
  BoundarySolve boundary;                  ///< solver mesh, max edge and its rule, φ and q
  Eigen::MatrixX3d points;                 ///< #P×3 evaluation points [model units]
  std::optional<PointGrid> grid;           ///< the grid the points are the nodes of, if any
  bem::PotentialField field;               ///< s (#P×3), ∇s (#P×9), winding number, inside
  features::FeatureParameters parameters;  ///< h0, a and the skeleton width used
  features::FeatureField<3> features;      ///< f_h, h_f, h_p, n_f, skeleton, … per point
  /// Inside points where h_f or h_p was clamped to 0 (inverse thickness above 1/a,
  /// features/thickness.hpp): only discretisation error produces that.
  Eigen::Index clamped_points = 0;
  /// Wall time of the stages: "read" (file input only), "refine", "assemble", "solve",
  /// "evaluate", "features".
  StageTimes times;
};

/// The features at `points` (#P×3 [model units]) of the solid bounded by `input`. Throws as
/// measure_thickness does.
FeaturesResult measure_features(const geometry::PreparedMesh& input,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                const FeaturesOptions& options,
                                const ProgressCallback& progress = {});

/// The features at the nodes of grid_over(bounding box, spacing). Throws ResourceError,
/// before the solve, when the grid has more than kMaxPoints nodes.
FeaturesResult measure_features_on_grid(const geometry::PreparedMesh& input, double spacing,
                                        const FeaturesOptions& options,
                                        const ProgressCallback& progress = {});

/// The same two for a mesh file, read, validated and repaired first (stage "read").
FeaturesResult measure_features(const std::filesystem::path& file,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                const FeaturesOptions& options,
                                const ProgressCallback& progress = {});
FeaturesResult measure_features_on_grid(const std::filesystem::path& file, double spacing,
                                        const FeaturesOptions& options,
                                        const ProgressCallback& progress = {});

}  // namespace bemshape::analysis
