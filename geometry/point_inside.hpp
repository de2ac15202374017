#pragma once
// Inside/outside classification of points against a closed triangle mesh (one or several
// shells, cavities included: a point in a cavity is outside the solid). Ray casting with
// exact predicates (CGAL Side_of_triangle_mesh), so the answer is robust for points near
// faces, edges and vertices. Built once; queries are const and thread-safe and the batch
// query runs in parallel (OpenMP). Used by the voxel FEM and by interior evaluation.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

namespace detail {
class SideOfTriangleMesh;
}

enum class Side : signed char { outside = -1, on_boundary = 0, inside = 1 };

class PointInsideQuery {
 public:
  /// Throws InputError if the mesh is not a closed 2-manifold (prepare it first).
  explicit PointInsideQuery(const SurfaceMesh& closed_mesh);
  ~PointInsideQuery();
  PointInsideQuery(PointInsideQuery&&) noexcept;
  PointInsideQuery& operator=(PointInsideQuery&&) noexcept;

  Side side(const Eigen::Vector3d& point) const;
  /// True if strictly inside the solid.
  bool inside(const Eigen::Vector3d& point) const { return side(point) == Side::inside; }
  /// points: #P×3 [model units] → #P sides.
  std::vector<Side> sides(const Eigen::Ref<const Eigen::MatrixX3d>& points) const;

 private:
  std::unique_ptr<detail::SideOfTriangleMesh> side_;
};

}  // namespace bemshape::geometry
