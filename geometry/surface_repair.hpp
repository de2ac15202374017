#pragma once
// Repairs that change the surface, each confined to a region no larger than the repair
// length ℓ (MeshPreparationOptions::repair_length; default kRepairRelativeLength of the
// bounding-box diagonal), plus the union of overlapping bodies, which does not change the
// solid at all:
//
//   holes            open edges whose end points coincide are stitched; a connected piece
//                    with open edges that is at most ℓ across is removed whole (a loose flap
//                    or sliver: no solid can be made of it); every other hole whose rim is at
//                    most ℓ across (bounding-box diagonal of its vertices) and has at most
//                    kMaxHoleEdges edges is filled by a triangulation refined to the rim's
//                    edge length and faired (bi-harmonic), so a patch on a curved surface
//                    continues it smoothly and a planar rim gets a flat patch;
//   self-crossings   a group of shells joined by crossing face pairs, one of which crosses
//                    itself, is split along the curves where it crosses and replaced by the
//                    boundary of the region it encloses, the points of positive winding
//                    number (winding_number_boundary.hpp), whatever its size — when that is
//                    the solid it was meant to bound: when its crossing is an overlap of
//                    sheets (w = 2, as bodies of one shell that were not united) and it is
//                    nowhere inside out beyond slivers (kInsideOutShare). Where it is inside
//                    out with no overlap (a patch pushed through the opposite wall: w = −1),
//                    the intended solid cannot be told and the repairs below are tried
//                    instead;
//   self-intersections within one shell
//                    in each cluster of intersecting faces (connected through intersecting
//                    pairs) the faces at most ℓ across are cut out, in successive attempts
//                    with 0 to kMaxIntersectionRings rings of such neighbours, and the holes
//                    refilled as above; the cut region must stay within ℓ (a vertex pushed
//                    through a large flat face is cleared by replacing the small faces
//                    around it, the large face stays);
//   overlapping bodies
//                    shells that cross each other are replaced by the boundary of their
//                    union (CGAL corefinement). This is the solid the file describes under
//                    the positive fill rule of the 3MF core specification (§4.1.1: the solid
//                    is the set of points of positive winding number), and what slicers
//                    print; the points inside any body stay inside. Shells of opposite
//                    orientation that cross (a cavity wall crossing an outer skin) are not
//                    united: which of them is the cavity cannot be told.
//
// What is left is reported region by region (IntersectionRepair::unresolved) with the reason,
// for the caller to measure around (mesh_preparation.hpp) or refuse.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "geometry/defect_zones.hpp"
#include "geometry/self_intersection.hpp"

namespace bemshape::geometry {

/// Default repair length ℓ relative to the bounding-box diagonal: 2 %. Filling a hole or
/// replacing a fold 2 % of the part across changes the surface inside that region only;
/// the teapot's smallest opening is 5.6 % of its diagonal and stays refused, the 6-edge
/// holes of real CAD exports are well below. Callers that know the length the analysis
/// resolves (h0, the element size) should pass it instead.
inline constexpr double kRepairRelativeLength = 0.02;

/// Holes with more edges are not filled: CGAL's hole triangulation falls back to an O(n³)
/// search when its Delaunay-based one fails, which takes seconds at a few hundred edges.
inline constexpr std::size_t kMaxHoleEdges = 500;

/// Rings of neighbouring faces cut out with a self-intersecting cluster in successive
/// attempts (0, 1, 2, 3): each attempt gives the refilled patch more room to clear the
/// opposite surface.
inline constexpr int kMaxIntersectionRings = 3;

/// When a self-crossing surface counts as one whose solid is clear: its crossing is an
/// overlap of sheets (w = 2, as bodies of one shell never united), beside which any region
/// of negative winding number is at most kInsideOutShare of the overlap's volume — the
/// slivers inside a fold bent tighter than the sheet is thick (1e-4 to 1e-3 of the overlap
/// on the folded strips of tests/support/damaged_meshes.hpp) — plus rounding, at most
/// kRoundingVolume of the enclosed volume. A patch pushed through the opposite wall, a
/// cavity wall crossing an outer skin or a fold of one skin leaves negative volume and no
/// overlap: whether a dent or a hole was meant cannot be told.
inline constexpr double kInsideOutShare = 0.01;
inline constexpr double kRoundingVolume = 1e-9;

/// One change made to the surface.
struct SurfaceRepairStep {
  /// A point of the repaired region (hole centre, cluster centre, centre of the curves where
  /// united bodies cross) [model units].
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  /// Its size: bounding-box diagonal of the hole rim, the loose piece, the cut region or the
  /// curves where united bodies cross [model units].
  double size = 0.0;
  std::size_t faces_removed = 0;
  std::size_t faces_added = 0;
  /// One line for the report, e.g. "filled a hole of 6 edges, 3.2 across, at (1, 2, 3) with
  /// 8 triangles (area 4.1; rim flat to 0.002)".
  std::string description;
};

struct HoleClosing {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  std::size_t edges_stitched = 0;
  std::vector<SurfaceRepairStep> pieces_removed;
  std::vector<SurfaceRepairStep> holes_filled;
  /// Holes left open: too large, too many edges, or the filling failed.
  std::size_t holes_left = 0;
  std::size_t edges_left = 0;
  double largest_left = 0.0;  // rim bounding-box diagonal [model units]
  Eigen::Vector3d first_left = Eigen::Vector3d::Zero();
  /// Why the first hole left was not filled.
  std::string why_left;
};

/// Stitches, removes loose pieces and fills holes as described above. The mesh must be
/// consistently oriented with at most two faces per edge and one fan per vertex
/// (split_nonmanifold, orient_consistently); otherwise it is returned unchanged.
///   repair_length: ℓ [model units].
HoleClosing close_small_holes(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                              double repair_length);

/// Bodies of one soup that share faces once welded (the same triangle in both, as when two
/// solids on one grid are exported without being united), replaced by the boundary of the
/// region they enclose (winding_number_boundary): the union, where dropping the duplicates
/// would leave holes and edges of three or four faces. Tried only when the welded soup has
/// duplicate faces and is closed as a chain (each edge used as often in each direction);
/// `ok` false (and the soup left to the other repairs) when it is not, or when the region
/// is inside out anywhere beyond slivers (kInsideOutShare, kRoundingVolume).
struct SharedFaceUnion {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  bool ok = false;
  /// The change, for the report (volume as given, overlaps counted twice, and after).
  SurfaceRepairStep step;
};

SharedFaceUnion unite_bodies_sharing_faces(const Eigen::MatrixX3d& vertices,
                                           const Eigen::MatrixX3i& faces);

struct IntersectionRepair {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// Intersecting pairs found at the start within one shell and between shells.
  std::size_t pairs_within_shells = 0;
  std::size_t pairs_between_shells = 0;
  std::vector<SurfaceRepairStep> clusters_replaced;
  std::vector<SurfaceRepairStep> unions;
  /// Groups of shells replaced by the boundary of the region they enclose, and their volumes
  /// as given (∫ w dV: overlaps counted as often as covered) and after [model units³].
  std::vector<SurfaceRepairStep> crossings_resolved;
  double resolved_volume_before = 0.0;
  double resolved_volume_after = 0.0;
  /// Signed volume after minus before the repairs of clusters within shells [model units³].
  double volume_change = 0.0;
  /// What is left: the pairs still intersecting, where, and why they were not repaired.
  SelfIntersections left;
  /// Bodies crossing along shared edges (crossing_edges) that were not united.
  bool crossings_left = false;
  std::string why_left;
  /// The regions still crossing (clusters of `left`'s pairs, and the edges of
  /// crossings_left), each with why it was not repaired.
  std::vector<DefectZone> unresolved;
};

/// Resolves the self-intersections `found` of a closed, consistently oriented mesh with at
/// most two faces per edge as described above, and tests the result again. Bodies with an
/// edge at one of `crossing_edges` (end points [model units]; NonmanifoldSplit::
/// crossing_edges) cross along it and are united too.
///   repair_length: ℓ [model units].
IntersectionRepair resolve_self_intersections(
    const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
    const SelfIntersections& found, double repair_length,
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& crossing_edges = {});

}  // namespace bemshape::geometry
