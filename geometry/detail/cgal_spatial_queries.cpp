// The one translation unit that compiles CGAL's AABB tree and Side_of_triangle_mesh.
#include "geometry/detail/cgal_spatial_queries.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::geometry::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TrianglePrimitive =
    CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using TriangleAabb = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>>;
using Mesh = CGAL::Surface_mesh<Point>;
using MeshPrimitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using MeshAabb = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, MeshPrimitive>>;

Point point(const Eigen::MatrixX3d& v, int i) {
  return Point(v(i, 0), v(i, 1), v(i, 2));
}

}  // namespace

struct TriangleTree::Impl {
  std::vector<Triangle> triangles;
  std::vector<Eigen::Index> face_of;  // input face of each stored triangle
  TriangleAabb tree;
};

TriangleTree::TriangleTree(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces)
    : impl_(std::make_unique<Impl>()) {
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Triangle t(point(vertices, faces(f, 0)), point(vertices, faces(f, 1)),
                     point(vertices, faces(f, 2)));
    // Degenerate triangles are covered by their neighbours and break the distance kernel.
    if (t.is_degenerate())
      continue;
    impl_->triangles.push_back(t);
    impl_->face_of.push_back(f);
  }
  if (impl_->triangles.empty())
    throw InputError("closest-point query: the mesh has no non-degenerate face");
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

TriangleTree::~TriangleTree() = default;
TriangleTree::TriangleTree(TriangleTree&&) noexcept = default;
TriangleTree& TriangleTree::operator=(TriangleTree&&) noexcept = default;

std::pair<Eigen::Index, Eigen::Vector3d> TriangleTree::closest(const Eigen::Vector3d& x) const {
  const auto [p, primitive] = impl_->tree.closest_point_and_primitive(Point(x(0), x(1), x(2)));
  const auto i = static_cast<std::size_t>(primitive - impl_->triangles.cbegin());
  return {impl_->face_of[i], Eigen::Vector3d(p.x(), p.y(), p.z())};
}

struct SideOfTriangleMesh::Impl {
  Mesh mesh;
  std::unique_ptr<MeshAabb> tree;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<Mesh, Kernel, CGAL::Default, MeshAabb>> side;
};

SideOfTriangleMesh::SideOfTriangleMesh(const Eigen::MatrixX3d& vertices,
                                       const Eigen::MatrixX3i& faces)
    : impl_(std::make_unique<Impl>()) {
  Mesh& mesh = impl_->mesh;
  std::vector<Mesh::Vertex_index> vh;
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    vh.push_back(mesh.add_vertex(point(vertices, static_cast<int>(v))));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (mesh.add_face(vh[static_cast<std::size_t>(faces(f, 0))],
                      vh[static_cast<std::size_t>(faces(f, 1))],
                      vh[static_cast<std::size_t>(faces(f, 2))]) == Mesh::null_face())
      throw InputError("inside/outside query: the mesh is not a manifold (face " +
                       std::to_string(f) + ")");
  if (mesh.is_empty() || !CGAL::is_closed(mesh))
    throw InputError("inside/outside query: the mesh is not closed");
  // The tree is built here, not lazily on the first query, so that concurrent const queries
  // only read it.
  impl_->tree = std::make_unique<MeshAabb>(CGAL::faces(mesh).first, CGAL::faces(mesh).second, mesh);
  impl_->tree->build();
  impl_->side =
      std::make_unique<CGAL::Side_of_triangle_mesh<Mesh, Kernel, CGAL::Default, MeshAabb>>(
          *impl_->tree);
}

SideOfTriangleMesh::~SideOfTriangleMesh() = default;
SideOfTriangleMesh::SideOfTriangleMesh(SideOfTriangleMesh&&) noexcept = default;
SideOfTriangleMesh& SideOfTriangleMesh::operator=(SideOfTriangleMesh&&) noexcept = default;

int SideOfTriangleMesh::side(const Eigen::Vector3d& x) const {
  switch ((*impl_->side)(Point(x(0), x(1), x(2)))) {
    case CGAL::ON_BOUNDED_SIDE:
      return 1;
    case CGAL::ON_BOUNDARY:
      return 0;
    default:
      return -1;
  }
}

}  // namespace bemshape::geometry::detail
