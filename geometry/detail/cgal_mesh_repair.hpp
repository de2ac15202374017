#pragma once
// Internal: the CGAL Polygon_mesh_processing repairs that change the surface (stitching,
// hole filling, replacing faces), behind plain Eigen types so that CGAL is
// compiled in one translation unit (cgal_mesh_repair.cpp) and never appears in a header.
// Which defects are small enough to repair is decided by the caller (surface_repair.cpp);
// these functions only do what they are asked.
//
// Every function takes a consistently oriented mesh whose edges have at most two faces and
// whose vertices each have one fan of faces (nonmanifold_split.hpp, mesh_orientation.hpp),
// and returns arrays of the same kind. Vertex positions are kept exactly; new vertices (hole
// patches) are appended.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace bemshape::geometry::detail {

/// One closed loop of open boundary edges.
struct CgalHole {
  std::size_t edges = 0;
  /// Bounding-box diagonal of the loop's vertices [model units].
  double extent = 0.0;
  /// Mean of the loop's vertices [model units].
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  /// Largest distance of a loop vertex from the loop's least-squares plane [model units].
  double out_of_plane = 0.0;
  bool filled = false;
  /// Fairing (CGAL::Polygon_mesh_processing::fair, bi-harmonic) succeeded; without it the
  /// patch is the refined triangulation of minimal area.
  bool faired = false;
  std::size_t faces_added = 0;
  double area_added = 0.0;  // [model units²]
};

/// A connected piece of surface with open edges that was removed whole.
struct CgalLoosePiece {
  std::size_t faces = 0;
  double extent = 0.0;  // bounding-box diagonal [model units]
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  double area = 0.0;  // [model units²]
};

struct CgalHoleClosing {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// Pairs of open boundary edges with equal end points joined by stitch_borders.
  std::size_t edges_stitched = 0;
  std::vector<CgalLoosePiece> pieces_removed;
  /// Every loop of open edges left after stitching and removing loose pieces, filled or not.
  std::vector<CgalHole> holes;
};

/// 1. CGAL::Polygon_mesh_processing::stitch_borders (open edges whose end points coincide);
/// 2. removes every connected piece that has open edges and whose bounding-box diagonal is
///    at most `max_piece_extent`;
/// 3. fills every remaining hole whose bounding-box diagonal is at most `max_hole_extent` and
///    that has at most `max_hole_edges` edges with triangulate_refine_and_fair_hole (patch
///    edges as long as the rim's, bi-harmonic fairing so a curved surface continues smoothly;
///    a planar rim gives a flat patch).
CgalHoleClosing cgal_close_holes(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                 double max_piece_extent, double max_hole_extent,
                                 std::size_t max_hole_edges);

struct CgalFaceReplacement {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// Faces removed (the selection, grown by CGAL's expand_face_selection_for_removal where
  /// removing it alone would leave a non-manifold vertex).
  std::size_t faces_removed = 0;
  /// The holes the removal opened, each filled as in cgal_close_holes.
  std::vector<CgalHole> holes;
  bool all_filled = true;
};

/// Removes the faces with remove[f] != 0 and fills the holes this opens.
CgalFaceReplacement cgal_replace_faces(const Eigen::MatrixX3d& vertices,
                                       const Eigen::MatrixX3i& faces,
                                       const std::vector<char>& remove);

}  // namespace bemshape::geometry::detail
