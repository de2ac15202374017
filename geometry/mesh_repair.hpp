#pragma once
// Mesh repair of faces that carry no geometry: collapsed faces (a repeated vertex after
// welding), duplicated faces and zero-area faces (three distinct collinear corners). Each is
// removed without opening a hole; orientation repair is in mesh_orientation.hpp.

#include <Eigen/Core>
#include <cstddef>

namespace bemshape::geometry {

struct FaceCleanup {
  /// #V×3 vertices still used by a face [model units]; #F×3 remaining faces.
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// Faces that repeated a vertex, dropped (their edges are covered twice by their
  /// neighbours, so no hole opens).
  std::size_t collapsed_removed = 0;
  /// Faces with the same three vertices as an earlier face, dropped (the first is kept).
  std::size_t duplicates_removed = 0;
  /// Zero-area faces removed by splitting their neighbour across the longest edge at the
  /// middle corner: the neighbour's two halves cover it exactly and share the degenerate
  /// face's two short edges, so the surface stays closed and its geometry is unchanged.
  std::size_t zero_area_removed = 0;
  /// Zero-area faces that could not be removed (the longest edge is a boundary or
  /// non-manifold edge); validation reports them.
  std::size_t zero_area_left = 0;
  /// Vertices no face refers to any more, dropped.
  std::size_t unreferenced_removed = 0;
};

/// Removes collapsed, duplicate and zero-area faces (zero area as defined by
/// kZeroAreaRelativeHeight in mesh_validation.hpp) as described above.
///   vertices: #V×3 [model units]; faces: #F×3 indices into vertices.
FaceCleanup remove_degenerate_faces(const Eigen::MatrixX3d& vertices,
                                    const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
