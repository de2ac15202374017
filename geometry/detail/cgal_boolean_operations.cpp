// The translation unit that compiles CGAL's corefinement (slow to compile).
#include "geometry/detail/cgal_boolean_operations.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::geometry::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

Mesh to_surface_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                     const char* operand) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vh(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    vh[static_cast<std::size_t>(v)] =
        mesh.add_vertex(Point(vertices(v, 0), vertices(v, 1), vertices(v, 2)));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (mesh.add_face(vh[static_cast<std::size_t>(faces(f, 0))],
                      vh[static_cast<std::size_t>(faces(f, 1))],
                      vh[static_cast<std::size_t>(faces(f, 2))]) == Mesh::null_face())
      throw InputError(std::string("Boolean operation: face ") + std::to_string(f) + " of the " +
                       operand + " operand is non-manifold");
  if (!CGAL::is_closed(mesh))
    throw InputError(std::string("Boolean operation: the ") + operand +
                     " operand is not a closed surface");
  // The rest of the corefinement's precondition. CGAL does not check it in a release
  // build: an operand that crosses itself (including one with a zero-area face, which CGAL
  // counts as crossing itself) or whose faces do not bound a volume made the corefinement
  // read outside its arrays (docs/reliability.md, "Fuzzing").
  if (PMP::does_self_intersect(mesh))
    throw InputError(std::string("Boolean operation: the ") + operand +
                     " operand intersects itself or has a zero-area face");
  if (!PMP::does_bound_a_volume(mesh))
    throw InputError(std::string("Boolean operation: the ") + operand +
                     " operand does not bound a volume (its shells are nested with "
                     "inconsistent orientations)");
  return mesh;
}

}  // namespace

void cgal_boolean(const Eigen::MatrixX3d& vertices_a, const Eigen::MatrixX3i& faces_a,
                  const Eigen::MatrixX3d& vertices_b, const Eigen::MatrixX3i& faces_b,
                  BooleanOperation operation, Eigen::MatrixX3d& vertices,
                  Eigen::MatrixX3i& faces) {
  Mesh a = to_surface_mesh(vertices_a, faces_a, "first");
  Mesh b = to_surface_mesh(vertices_b, faces_b, "second");
  Mesh result;
  const bool ok = operation == BooleanOperation::union_of
                      ? PMP::corefine_and_compute_union(a, b, result)
                      : PMP::corefine_and_compute_difference(a, b, result);
  if (!ok)
    throw InputError(
        "Boolean operation: CGAL's corefinement could not represent the result as a "
        "manifold surface (operands touching along an edge or a vertex?)");
  PMP::triangulate_faces(result);
  std::vector<int> index(result.num_vertices(), -1);
  vertices.resize(static_cast<Eigen::Index>(result.number_of_vertices()), 3);
  int next = 0;
  for (Mesh::Vertex_index v : result.vertices()) {
    const Point& p = result.point(v);
    vertices.row(next) << p.x(), p.y(), p.z();
    index[static_cast<std::size_t>(v.idx())] = next++;
  }
  faces.resize(static_cast<Eigen::Index>(result.number_of_faces()), 3);
  Eigen::Index f = 0;
  for (Mesh::Face_index fi : result.faces()) {
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(result.halfedge(fi), result))
      faces(f, k++) = index[static_cast<std::size_t>(v.idx())];
    ++f;
  }
}

}  // namespace bemshape::geometry::detail
