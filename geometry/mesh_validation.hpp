#pragma once
// Mesh validation: the combinatorial and per-face checks that decide whether a welded
// triangle mesh bounds a solid. Self-intersections (self_intersection.hpp) and the
// orientation of each shell relative to the solid (mesh_orientation.hpp) are separate.
//
// Rules, each counted with the position of its first offender:
//   boundary edge      an edge used by exactly one face: the surface has a hole;
//   non-manifold edge  an edge used by three or more faces;
//   non-manifold vertex a vertex whose faces form two or more fans joined only at it;
//   collapsed face     a face that repeats a vertex (after welding);
//   zero-area face     three distinct corners whose height is ≤ kZeroAreaRelativeHeight of
//                      the longest edge (collinear corners: no normal);
//   needle face        height < kNeedleRelativeHeight of the longest edge (legal geometry,
//                      reported because such slivers need remeshing before a BEM solve);
//   duplicate face     the same three vertices as an earlier face (either orientation);
//   inconsistent edge  an edge of two faces that both traverse it in the same direction
//                      (their normals disagree about which side is outside).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace bemshape::geometry {

/// Heights below 1e-9 of the longest edge are flat to within the rounding of double
/// arithmetic on float32 input: the normal of such a face is numerically meaningless.
inline constexpr double kZeroAreaRelativeHeight = 1e-9;

/// Faces with height below 1e-3 of their longest edge (angles under ~0.1°) are reported as
/// needles/caps: fine for validation and remeshing, bad for BEM quadrature on the raw mesh.
inline constexpr double kNeedleRelativeHeight = 1e-3;

/// How many elements break one rule, and where the first one is.
struct Finding {
  std::size_t count = 0;
  /// Position of the first offender [model units]: an edge's midpoint, a vertex, or a
  /// face's centroid.
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  void add(const Eigen::Vector3d& where) {
    if (count++ == 0)
      first = where;
  }
  explicit operator bool() const { return count > 0; }
};

struct MeshValidation {
  Finding boundary_edges;
  Finding nonmanifold_edges;
  Finding nonmanifold_vertices;
  Finding collapsed_faces;
  Finding zero_area_faces;
  Finding needle_faces;
  Finding duplicate_faces;
  Finding inconsistent_edges;
  /// Edge-connected components of the faces (collapsed faces excluded).
  std::size_t shells = 0;

  /// No holes, no non-manifold edges or vertices: every edge has exactly two faces.
  bool closed_manifold() const {
    return !boundary_edges && !nonmanifold_edges && !nonmanifold_vertices;
  }
};

/// Runs every rule above on a welded mesh.
///   vertices: #V×3 [model units]; faces: #F×3 indices into vertices.
MeshValidation validate_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

/// Height of face f relative to its longest edge, 2·area / longest²; 0 for a collapsed face.
double relative_height(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                       Eigen::Index f);

/// Edge-connected components: label[f] ∈ [0, count) for each face, −1 for collapsed faces.
/// Two faces are connected when they share an edge (through any number of faces).
std::vector<int> shell_labels(const Eigen::MatrixX3i& faces, std::size_t* count = nullptr);

}  // namespace bemshape::geometry
