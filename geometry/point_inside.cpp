#include "geometry/point_inside.hpp"

#include "geometry/detail/cgal_spatial_queries.hpp"

namespace bemshape::geometry {

PointInsideQuery::PointInsideQuery(const SurfaceMesh& closed_mesh)
    : side_(std::make_unique<detail::SideOfTriangleMesh>(closed_mesh.vertices(),
                                                         closed_mesh.faces())) {}

PointInsideQuery::~PointInsideQuery() = default;
PointInsideQuery::PointInsideQuery(PointInsideQuery&&) noexcept = default;
PointInsideQuery& PointInsideQuery::operator=(PointInsideQuery&&) noexcept = default;

Side PointInsideQuery::side(const Eigen::Vector3d& point) const {
  return static_cast<Side>(side_->side(point));
}

std::vector<Side> PointInsideQuery::sides(const Eigen::Ref<const Eigen::MatrixX3d>& points) const {
  std::vector<Side> result(static_cast<std::size_t>(points.rows()));
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    result[static_cast<std::size_t>(i)] = side(Eigen::Vector3d(points.row(i).transpose()));
  return result;
}

}  // namespace bemshape::geometry
