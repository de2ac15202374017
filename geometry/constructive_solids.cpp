#include "geometry/constructive_solids.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "geometry/detail/cgal_boolean_operations.hpp"

namespace bemshape::geometry {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double signed_area(const Polygon2& p) {
  double area = 0.0;
  for (Eigen::Index i = 0, n = p.rows(); i < n; ++i)
    area += cross2(p.row(i).transpose(), p.row((i + 1) % n).transpose());
  return 0.5 * area;
}

/// Ear clipping of a simple counter-clockwise polygon: #P − 2 triangles, counter-clockwise.
std::vector<Eigen::Vector3i> triangulate_polygon(const Polygon2& p) {
  std::vector<int> left(static_cast<std::size_t>(p.rows()));
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = static_cast<int>(i);
  std::vector<Eigen::Vector3i> triangles;
  auto corner = [&](int i) -> Eigen::Vector2d { return p.row(i).transpose(); };
  while (left.size() > 3) {
    bool clipped = false;
    const std::size_t n = left.size();
    for (std::size_t k = 0; k < n && !clipped; ++k) {
      const int a = left[(k + n - 1) % n], b = left[k], c = left[(k + 1) % n];
      const Eigen::Vector2d pa = corner(a), pb = corner(b), pc = corner(c);
      if (cross2(pb - pa, pc - pb) <= 0.0) continue;  // reflex or straight corner
      bool empty = true;
      for (int other : left) {
        if (other == a || other == b || other == c) continue;
        const Eigen::Vector2d q = corner(other);
        if (cross2(pb - pa, q - pa) >= 0.0 && cross2(pc - pb, q - pb) >= 0.0 &&
            cross2(pa - pc, q - pc) >= 0.0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      triangles.emplace_back(a, b, c);
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped)
      throw InputError("extrude_polygon: the polygon of " + std::to_string(p.rows()) +
                       " corners is not simple (no ear left to clip)");
  }
  triangles.emplace_back(left[0], left[1], left[2]);
  return triangles;
}

SurfaceMesh boolean(const SurfaceMesh& a, const SurfaceMesh& b,
                    detail::BooleanOperation operation) {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  detail::cgal_boolean(a.vertices(), a.faces(), b.vertices(), b.faces(), operation, vertices,
                       faces);
  return SurfaceMesh(std::move(vertices), std::move(faces));
}

}  // namespace

SurfaceMesh extrude_polygon(const Polygon2& polygon, double z0, double z1) {
  const Eigen::Index n = polygon.rows();
  if (n < 3) throw InputError("extrude_polygon: a polygon needs at least 3 corners");
  if (!(signed_area(polygon) > 0.0))
    throw InputError("extrude_polygon: the polygon is not counter-clockwise");
  if (!(z1 > z0)) throw InputError("extrude_polygon: needs z0 < z1");
  Eigen::MatrixX3d vertices(2 * n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    vertices.row(i) << polygon(i, 0), polygon(i, 1), z0;
    vertices.row(n + i) << polygon(i, 0), polygon(i, 1), z1;
  }
  const std::vector<Eigen::Vector3i> cap = triangulate_polygon(polygon);
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(2 * cap.size()) + 2 * n, 3);
  Eigen::Index f = 0;
  for (const Eigen::Vector3i& t : cap) {
    faces.row(f++) << t(0), t(2), t(1);                 // bottom, facing −z
    faces.row(f++) << n + t(0), n + t(1), n + t(2);     // top, facing +z
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = (i + 1) % n;
    faces.row(f++) << i, j, n + j;
    faces.row(f++) << i, n + j, n + i;
  }
  return SurfaceMesh(std::move(vertices), std::move(faces));
}

SurfaceMesh make_box_solid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Polygon2 rectangle(4, 2);
  rectangle << lo.x(), lo.y(), hi.x(), lo.y(), hi.x(), hi.y(), lo.x(), hi.y();
  return extrude_polygon(rectangle, lo.z(), hi.z());
}

Polygon2 circle_polygon(const Eigen::Vector2d& centre, double radius, int segments,
                        double phase) {
  if (segments < 3) throw InputError("circle_polygon: needs at least 3 segments");
  Polygon2 p(segments, 2);
  for (int i = 0; i < segments; ++i) {
    const double angle = phase + 2.0 * std::numbers::pi * i / segments;
    p.row(i) << centre.x() + radius * std::cos(angle), centre.y() + radius * std::sin(angle);
  }
  return p;
}

SurfaceMesh make_faceted_cylinder(const Eigen::Vector2d& centre, double radius, double z0,
                                  double z1, int segments) {
  return extrude_polygon(circle_polygon(centre, radius, segments), z0, z1);
}

SurfaceMesh transformed(const SurfaceMesh& mesh, const Eigen::Affine3d& motion) {
  if (!(motion.linear().determinant() > 0.0))
    throw InputError("transformed: the map must preserve orientation");
  Eigen::MatrixX3d vertices = (motion * mesh.vertices().transpose()).transpose();
  Eigen::MatrixX3i faces = mesh.faces();
  return SurfaceMesh(std::move(vertices), std::move(faces));
}

SurfaceMesh mesh_union(const SurfaceMesh& a, const SurfaceMesh& b) {
  return boolean(a, b, detail::BooleanOperation::union_of);
}

SurfaceMesh mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b) {
  return boolean(a, b, detail::BooleanOperation::difference);
}

}  // namespace bemshape::geometry
