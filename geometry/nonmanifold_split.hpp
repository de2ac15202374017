#pragma once
// Splitting non-manifold edges and vertices: the surface is cut, never moved, so that every
// edge has at most two faces and the faces around every vertex form one fan. Nothing
// geometric changes; only which faces share which vertex copies.
//
// Non-manifold edge (k ≥ 3 faces): the faces are sorted by the angle of their third vertex
// around the edge axis. Faces of one piece of surface (connected through manifold edges) are
// paired among themselves, so every body stays whole; the faces left over (a fin, open
// sheets) are paired among themselves. Within each group the pairing is one of angular
// neighbours — in a solid, two faces that belong together bound a wedge of material with no
// other face inside it — and the one that scores best, each pair scoring
//   4 if both faces lie in the same piece,
//   2 if they traverse the edge in opposite directions (orientation consistent),
//   1 if the wedge between them is material by the orientation of their piece (when that
//     piece is closed and so has a sign of volume).
// Two cubes sharing an edge become two cubes touching along it. With an odd number of
// leftovers one face is left alone: its edge becomes an open boundary edge (stitching, hole
// filling or the removal of a loose piece deals with it; mesh_preparation.hpp).
//
// Crossing bodies: when, going around the edge with the faces' orientation, some wedge lies
// inside two bodies (winding number 2), the bodies do not touch there but pass through each
// other, and their surfaces meet along the edge (welding made the intersection curve a shared
// edge, which no face-pair intersection test sees). The faces are paired as above all the
// same, and the edge is listed in crossing_edges so that the caller unites the shells that
// meet there (surface_repair.hpp): whichever closed surfaces the pairing made (the two
// bodies, or the boundaries of their union and of their intersection), their union is the
// union of the bodies.
//
// Non-manifold vertex: after the edges are split, the faces around each vertex are grouped
// into fans (connected through the edges at the vertex); each fan after the first gets its
// own copy of the vertex (what CGAL's duplicate_non_manifold_vertices does on a halfedge
// mesh).

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

namespace bemshape::geometry {

struct NonmanifoldSplit {
  /// #V'×3 vertices [model units]: the input's, then the copies made by the split.
  Eigen::MatrixX3d vertices;
  /// #F×3 faces, same order as the input, re-indexed to the copies.
  Eigen::MatrixX3i faces;
  /// Edges that had three or more faces, and the midpoint of the first [model units].
  std::size_t edges_split = 0;
  Eigen::Vector3d first_edge = Eigen::Vector3d::Zero();
  /// Faces left without a partner at a split edge (odd number of faces there).
  std::size_t faces_unpaired = 0;
  /// Split edges along which two bodies cross (their faces alternate around the edge), the
  /// midpoint of the first, and the end points of each [model units].
  std::size_t edges_crossing = 0;
  Eigen::Vector3d first_crossing = Eigen::Vector3d::Zero();
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> crossing_edges;
  /// Vertices whose faces formed several fans, and the first of them [model units].
  std::size_t vertices_split = 0;
  Eigen::Vector3d first_vertex = Eigen::Vector3d::Zero();
  /// Vertex copies added (Σ over split vertices of fans − 1).
  std::size_t copies_added = 0;
};

/// Splits every non-manifold edge and vertex of a welded mesh without collapsed faces, as
/// described above. A mesh without such edges and vertices comes back unchanged.
///   vertices: #V×3 [model units]; faces: #F×3 indices into vertices.
NonmanifoldSplit split_nonmanifold(const Eigen::MatrixX3d& vertices,
                                   const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
