#pragma once
// Vertex welding: merging coincident vertices so that a triangle soup (STL stores every
// facet's corners separately) gets the shared edges that validation and the solver need.

#include <Eigen/Core>
#include <cstddef>

namespace bemshape::geometry {

/// Tolerance for merging nearly coincident vertices, relative to the bounding-box diagonal.
/// 1e-6 is about ten float32 rounding steps (relative precision 6e-8) at the scale of the
/// part: CAD exporters round the same corner slightly differently in different facets, and
/// STL stores float32. It is also three orders of magnitude below the smallest feature a BEM
/// mesh resolves (elements are rarely shorter than 1e-3 of the diagonal), so distinct
/// vertices are never merged in practice.
inline constexpr double kWeldRelativeTolerance = 1e-6;

/// A welded mesh and what welding did.
struct WeldResult {
  /// #V×3 distinct vertex positions [model units] (only vertices some face uses).
  Eigen::MatrixX3d vertices;
  /// #F×3 faces re-indexed into `vertices`; same count and order as the input faces. A
  /// face may now repeat a vertex (it collapsed); repair removes such faces.
  Eigen::MatrixX3i faces;
  /// Vertices merged because their coordinates were exactly equal.
  std::size_t merged_exact = 0;
  /// Vertices merged because they were closer than `tolerance` (after the exact stage).
  std::size_t merged_within_tolerance = 0;
  /// Vertices no face refers to, dropped.
  std::size_t unreferenced_removed = 0;
  /// Absolute merge distance used [model units].
  double tolerance = 0.0;
};

/// Merges vertices in two stages: exactly equal positions, then positions within
/// `relative_tolerance` × (bounding-box diagonal) of an earlier kept vertex (greedy in index
/// order, so the result is deterministic and no merged vertex moves by more than the
/// tolerance). Unreferenced vertices are dropped.
///   vertices: #V×3 [model units]; faces: #F×3 indices into vertices.
WeldResult weld_vertices(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                         double relative_tolerance = kWeldRelativeTolerance);

}  // namespace bemshape::geometry
