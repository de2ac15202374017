#pragma once
// Internal: the graded remesher (geometry/graded_remeshing.hpp) on CGAL's Surface_mesh and
// Euler operations, behind Eigen types so that CGAL stays in one translation unit
// (cgal_graded_remeshing.cpp).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <vector>

namespace bemshape::geometry::detail {

struct GradedRemeshInput {
  const Eigen::MatrixX3d* vertices = nullptr;
  const Eigen::MatrixX3i* faces = nullptr;
  /// Crease edges (input vertex pairs): only split, at their midpoints.
  std::vector<std::array<int, 2>> creases;
  /// #V: crease corners, never moved or removed.
  const std::vector<char>* corner = nullptr;
  /// If true, some crease vertices that are not corners lie where a crease turns (a curved
  /// crease, geometry/surface_creases.hpp): every vertex on a crease is then put back onto
  /// the input's crease polygon (its closest point) after it slides or is made by a split.
  bool curved_creases = false;
  /// #F patch of each input face (faces joined without crossing a crease).
  const Eigen::VectorXi* face_patch = nullptr;
  int patches = 0;
  /// Target edge length h(x) [model units]; called from one thread.
  std::function<double(const Eigen::Vector3d&)> size;
  unsigned iterations = 0;
  /// Operations other than splits never make a face's smallest angle fall below
  /// min(this, the smallest angle of the faces they replace) [rad].
  double min_angle = 0.0;
  /// Largest rotation of a face's normal an operation may cause [rad].
  double max_normal_turn = 0.0;
  /// Refuse to grow beyond this many faces (ResourceError).
  double max_faces = 0.0;
  /// If > 0: at the end, edges longer than this times h (at their ends) are split, so that
  /// no edge is longer than that.
  double max_edge_ratio = 0.0;
  /// Called with the fraction done after each pass; may throw to cancel.
  std::function<void(double)> progress;
};

struct GradedRemeshOutput {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  Eigen::VectorXi face_patch;  ///< #F: the patch of each output face
  long splits = 0, collapses = 0, flips = 0, moves = 0;
};

/// Remeshes a closed, consistently oriented manifold mesh. Throws InputError if the mesh is
/// not a closed manifold, ResourceError beyond max_faces.
GradedRemeshOutput cgal_graded_remesh(const GradedRemeshInput& input);

}  // namespace bemshape::geometry::detail
