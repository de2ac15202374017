#pragma once
// The surface mesh every module works on: a plain indexed triangle mesh.
//
//   vertices: #V×3 positions [model units: whatever the input file used]
//   faces:    #F×3 vertex indices, counter-clockwise seen from outside the solid, so that
//             the right-hand-rule normal n = (b−a)×(c−a)/|…| points out of the solid
//
// Per-face normals, areas and centroids are computed once at construction. A face of zero
// area gets a zero normal; mesh validation reports such faces and repair removes them.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace bemshape::geometry {

/// Axis-aligned bounding box [model units].
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  Eigen::Vector3d extent() const { return max - min; }
  double diagonal() const { return extent().norm(); }
};

class SurfaceMesh {
 public:
  SurfaceMesh() = default;
  /// Takes ownership of the arrays; throws InputError if an index is out of range or a
  /// coordinate is not finite.
  SurfaceMesh(Eigen::MatrixX3d vertices, Eigen::MatrixX3i faces);

  const Eigen::MatrixX3d& vertices() const noexcept { return vertices_; }
  const Eigen::MatrixX3i& faces() const noexcept { return faces_; }
  /// #F×3 unit outward normals (zero rows for zero-area faces).
  const Eigen::MatrixX3d& face_normals() const noexcept { return normals_; }
  /// #F face areas [model units²].
  const Eigen::VectorXd& face_areas() const noexcept { return areas_; }
  /// #F×3 face centroids [model units].
  const Eigen::MatrixX3d& face_centroids() const noexcept { return centroids_; }

  Eigen::Index num_vertices() const noexcept { return vertices_.rows(); }
  Eigen::Index num_faces() const noexcept { return faces_.rows(); }
  bool empty() const noexcept { return faces_.rows() == 0; }

  /// Corner k ∈ {0,1,2} of face f.
  Eigen::Vector3d corner(Eigen::Index f, int k) const {
    return vertices_.row(faces_(f, k)).transpose();
  }
  BoundingBox bounding_box() const;
  /// Total area Σ_f |T_f| [model units²].
  double area() const { return areas_.sum(); }
  /// Signed enclosed volume (1/3)∫ x·n dA [model units³]; positive for outward orientation.
  double signed_volume() const;
  /// Longest and mean edge length over all faces [model units].
  double max_edge_length() const;
  double mean_edge_length() const;
  /// Smallest interior angle of any face [degrees]; 180 for an empty mesh.
  double smallest_angle_degrees() const;

 private:
  Eigen::MatrixX3d vertices_;
  Eigen::MatrixX3i faces_;
  Eigen::MatrixX3d normals_;
  Eigen::VectorXd areas_;
  Eigen::MatrixX3d centroids_;
};

/// x ↦ scale·R·x + t applied to every vertex (R a rotation, scale > 0): used for invariance
/// checks and unit conversion. Orientation is preserved.
SurfaceMesh transformed(const SurfaceMesh& mesh, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation, double scale = 1.0);

/// The same mesh with every face's orientation reversed (normals flip).
SurfaceMesh with_flipped_orientation(const SurfaceMesh& mesh);

/// The disjoint union of two meshes (vertices of `b` are re-indexed after those of `a`).
SurfaceMesh concatenated(const SurfaceMesh& a, const SurfaceMesh& b);

}  // namespace bemshape::geometry
