// The translation unit that compiles CGAL's autorefinement (slow to compile). It is built
// with CGAL_DEBUG (geometry/CMakeLists.txt): CGAL 5.5's experimental autorefinement guards
// configurations it does not handle only by CGAL_assertion, which a release build compiles
// out (an empty vector is then read); with the assertions on, such a case throws
// CGAL::Assertion_exception, which is caught here. The other translation units keep
// CGAL's assertions off; the templates they share with this one differ only in those checks.
#include "geometry/detail/cgal_autorefinement.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <array>
#include <exception>
#include <memory>

#include "core/cancellation.hpp"

namespace bemshape::geometry::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using FaceIndex = Mesh::Face_index;
using VertexIndex = Mesh::Vertex_index;

Point point(const Eigen::Vector3d& x) {
  return {x.x(), x.y(), x.z()};
}

/// Follows which input face each new face is a piece of (CGAL splits a face f_old into
/// f_old itself and new faces, announced between before_subface_creations and
/// after_subface_creations), and polls cancellation at CGAL's progress steps. Visitors are
/// copied by value into the named parameters, so the state is shared through a pointer.
struct SourceTracker : PMP::Corefinement::Default_visitor<Mesh> {
  std::shared_ptr<std::vector<Eigen::Index>> source;
  Eigen::Index splitting = -1;

  explicit SourceTracker(std::shared_ptr<std::vector<Eigen::Index>> s) : source(std::move(s)) {}

  void before_subface_creations(FaceIndex f_old, Mesh&) {
    splitting = f_old.idx() < source->size() ? (*source)[f_old.idx()] : -1;
  }
  void after_subface_created(FaceIndex f_new, Mesh&) {
    if (source->size() <= f_new.idx())
      source->resize(f_new.idx() + 1, -1);
    (*source)[f_new.idx()] = splitting;
  }
  void progress_filtering_intersections(double) const { throw_if_cancelled(); }
  void triangulating_faces_step() const { throw_if_cancelled(); }
  void edge_face_intersections_step() const { throw_if_cancelled(); }
  void intersection_of_coplanar_faces_step() const { throw_if_cancelled(); }
};

}  // namespace

CgalAutorefinement cgal_autorefine(const Eigen::MatrixX3d& vertices,
                                   const Eigen::MatrixX3i& faces) {
  CgalAutorefinement result;
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    points.push_back(point(vertices.row(v).transpose()));
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    polygons.push_back({static_cast<std::size_t>(faces(f, 0)),
                        static_cast<std::size_t>(faces(f, 1)),
                        static_cast<std::size_t>(faces(f, 2))});
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    result.failure = "the surface is not a manifold, consistently oriented mesh";
    return result;
  }
  Mesh mesh;
  // In a new mesh, polygon_soup_to_polygon_mesh adds polygon i as face i.
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  auto source = std::make_shared<std::vector<Eigen::Index>>(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f)
    (*source)[f] = static_cast<Eigen::Index>(f);
  try {
    PMP::experimental::autorefine(mesh, CGAL::parameters::visitor(SourceTracker(source)));
  } catch (const CancelledError&) {
    throw;
  } catch (const ResourceError&) {
    throw;
  } catch (const std::exception& e) {
    // CGAL::Assertion_exception, Triple_intersection_exception, std::bad_alloc of an
    // exploding refinement: the surface is used as it is and the caller says why.
    result.failure = std::string("CGAL's autorefinement failed: ") + e.what();
    return result;
  }

  std::vector<int> index(mesh.num_vertices(), -1);
  result.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  int next = 0;
  for (VertexIndex v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    result.vertices.row(next) << p.x(), p.y(), p.z();
    index[v.idx()] = next++;
  }
  result.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  result.source.reserve(mesh.number_of_faces());
  Eigen::Index f = 0;
  for (FaceIndex fi : mesh.faces()) {
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(fi), mesh)) {
      if (k == 3) {
        result.failure = "CGAL's autorefinement returned a face with more than 3 corners";
        return result;
      }
      result.faces(f, k++) = index[v.idx()];
    }
    const Eigen::Index from = fi.idx() < source->size() ? (*source)[fi.idx()] : -1;
    if (k != 3 || from < 0) {
      result.failure = "CGAL's autorefinement returned a face it did not account for";
      return result;
    }
    result.source.push_back(from);
    ++f;
  }
  result.ok = true;
  return result;
}

int exact_orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d) {
  return static_cast<int>(CGAL::orientation(point(a), point(b), point(c), point(d)));
}

int exact_coplanar_orientation(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                               const Eigen::Vector3d& r, const Eigen::Vector3d& s) {
  return static_cast<int>(CGAL::coplanar_orientation(point(p), point(q), point(r), point(s)));
}

}  // namespace bemshape::geometry::detail
