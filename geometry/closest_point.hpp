#pragma once
// Closest point on a triangle mesh for many query points: the face, the barycentric
// coordinates on it and the distance. Used to carry a solution computed on a refined mesh
// back to the original mesh: for each original vertex x, u(x) ≈ Σ_k λ_k u(corner_k(face)).
// Backed by an AABB tree (CGAL) built once in the constructor; queries are const and
// thread-safe, and the batch query runs in parallel (OpenMP).

#include <Eigen/Core>
#include <memory>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

namespace detail {
class TriangleTree;
}

/// The nearest surface point to one query.
struct ClosestPoint {
  /// Face of the mesh the point lies on.
  Eigen::Index face = -1;
  /// Barycentric coordinates (λ0, λ1, λ2) ≥ 0, Σ = 1, w.r.t. the face's corners 0, 1, 2.
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  /// The point Σ λ_k corner_k [model units].
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// |query − point| [model units].
  double distance = 0.0;
};

/// The same for #P queries.
struct ClosestPoints {
  Eigen::VectorXi faces;         // #P
  Eigen::MatrixX3d barycentric;  // #P×3
  Eigen::MatrixX3d points;       // #P×3 [model units]
  Eigen::VectorXd distances;     // #P [model units]
};

class ClosestPointQuery {
 public:
  /// Copies what it needs from `mesh`; zero-area faces are skipped (their neighbours cover
  /// them). Throws InputError if the mesh has no face of positive area.
  explicit ClosestPointQuery(const SurfaceMesh& mesh);
  ~ClosestPointQuery();
  ClosestPointQuery(ClosestPointQuery&&) noexcept;
  ClosestPointQuery& operator=(ClosestPointQuery&&) noexcept;

  ClosestPoint closest(const Eigen::Vector3d& query) const;
  /// queries: #P×3 [model units].
  ClosestPoints closest_points(const Eigen::Ref<const Eigen::MatrixX3d>& queries) const;

 private:
  Eigen::MatrixX3d vertices_;
  Eigen::MatrixX3i faces_;
  std::unique_ptr<detail::TriangleTree> tree_;
};

/// Barycentric coordinates of the point of triangle (a, b, c) nearest to p (so always in
/// the triangle: λ ≥ 0, Σλ = 1).
Eigen::Vector3d barycentric_coordinates(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace bemshape::geometry
