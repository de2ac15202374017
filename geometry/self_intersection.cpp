#include "geometry/self_intersection.hpp"

#include "geometry/detail/cgal_mesh_algorithms.hpp"

namespace bemshape::geometry {

SelfIntersections find_self_intersections(const Eigen::MatrixX3d& vertices,
                                          const Eigen::MatrixX3i& faces) {
  detail::CgalSelfIntersections found = detail::cgal_self_intersections(vertices, faces);
  SelfIntersections result;
  result.pairs = found.pairs;
  result.face_pairs = std::move(found.list);
  if (!result.face_pairs.empty()) {
    const Eigen::Index f = result.face_pairs.front().first;
    result.first =
        (vertices.row(faces(f, 0)) + vertices.row(faces(f, 1)) + vertices.row(faces(f, 2)))
            .transpose() /
        3.0;
  }
  return result;
}

}  // namespace bemshape::geometry
