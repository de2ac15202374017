// One of the translation units that compile CGAL's Polygon_mesh_processing (slow to compile):
// self-intersections and remeshing.
#include "geometry/detail/cgal_mesh_algorithms.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <algorithm>
#include <array>
#include <limits>
#include <omp.h>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::geometry::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VertexIndex = Mesh::Vertex_index;
using FaceIndex = Mesh::Face_index;
using EdgeIndex = Mesh::Edge_index;

/// Builds a Surface_mesh; faces that cannot be added (non-manifold) are skipped and their
/// input indices returned through `skipped`. Face i of the result is input face face_of[i].
Mesh to_surface_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                     std::vector<Eigen::Index>& face_of, std::size_t& skipped) {
  Mesh mesh;
  std::vector<VertexIndex> vh(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    vh[static_cast<std::size_t>(v)] =
        mesh.add_vertex(Point(vertices(v, 0), vertices(v, 1), vertices(v, 2)));
  skipped = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const FaceIndex fi = mesh.add_face(vh[static_cast<std::size_t>(faces(f, 0))],
                                       vh[static_cast<std::size_t>(faces(f, 1))],
                                       vh[static_cast<std::size_t>(faces(f, 2))]);
    if (fi == Mesh::null_face())
      ++skipped;
    else
      face_of.push_back(f);
  }
  return mesh;
}

void to_arrays(const Mesh& mesh, Eigen::MatrixX3d& vertices, Eigen::MatrixX3i& faces) {
  std::vector<int> index(mesh.num_vertices(), -1);
  vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  int next = 0;
  for (VertexIndex v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    vertices.row(next) << p.x(), p.y(), p.z();
    index[static_cast<std::size_t>(v.idx())] = next++;
  }
  faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  Eigen::Index f = 0;
  for (FaceIndex fi : mesh.faces()) {
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(fi), mesh))
      if (k < 3)
        faces(f, k++) = index[static_cast<std::size_t>(v.idx())];
    if (k != 3)
      throw InternalError("isotropic remeshing produced a non-triangular face");
    ++f;
  }
}

/// A self-intersection scan splits into slabs (one per thread) from this many faces on per
/// slab: below it the copies of the boxes cost more than the second thread saves.
constexpr Eigen::Index kSelfIntersectionSlabFaces = 20000;

}  // namespace

CgalSelfIntersections cgal_self_intersections(const Eigen::MatrixX3d& vertices,
                                              const Eigen::MatrixX3i& faces) {
  CgalSelfIntersections result;
  // Vertices with equal coordinates get one identity (the first such vertex in the order of
  // their coordinates).
  const auto nv = static_cast<std::size_t>(vertices.rows());
  std::vector<int> identity(nv), order(nv);
  std::vector<Point> points(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const auto i = static_cast<Eigen::Index>(v);
    points[v] = Point(vertices(i, 0), vertices(i, 1), vertices(i, 2));
    order[v] = static_cast<int>(v);
  }
  auto key = [&](int v) {
    const auto i = static_cast<Eigen::Index>(v);
    return std::array<double, 3>{vertices(i, 0), vertices(i, 1), vertices(i, 2)};
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  for (std::size_t k = 0; k < nv; ++k)
    identity[static_cast<std::size_t>(order[k])] =
        k > 0 && key(order[k]) == key(order[k - 1])
            ? identity[static_cast<std::size_t>(order[k - 1])]
            : order[k];
  auto corner = [&](Eigen::Index f, int k) { return faces(f, k); };
  auto same = [&](int a, int b) {
    return identity[static_cast<std::size_t>(a)] == identity[static_cast<std::size_t>(b)];
  };
  auto p = [&](int v) -> const Point& { return points[static_cast<std::size_t>(v)]; };

  // A face with two corners at one position, or three collinear corners, has no interior
  // and no normal: it is reported as intersecting whatever its box meets (its neighbours at
  // least), so that the repairs cut it out, never passed over.
  std::vector<char> degenerate(static_cast<std::size_t>(faces.rows()), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    degenerate[static_cast<std::size_t>(f)] =
        same(corner(f, 0), corner(f, 1)) || same(corner(f, 1), corner(f, 2)) ||
        same(corner(f, 0), corner(f, 2)) ||
        CGAL::collinear(p(corner(f, 0)), p(corner(f, 1)), p(corner(f, 2)));

  auto intersect = [&](Eigen::Index f, Eigen::Index g) {
    if (degenerate[static_cast<std::size_t>(f)] || degenerate[static_cast<std::size_t>(g)])
      return true;
    // Corners of g matching corner k of f, by identity.
    int match[3] = {-1, -1, -1};
    int shared = 0;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        if (same(corner(f, k), corner(g, l))) {
          match[k] = l;
          ++shared;
          break;
        }
    if (shared >= 3)
      return true;  // the same triangle twice
    if (shared == 2) {
      // Shared edge (corners i, j of f); r and s are the third corners of f and g.
      int i = 0;
      while (match[i] < 0 || match[(i + 1) % 3] < 0)
        ++i;
      const int r = corner(f, (i + 2) % 3);
      const int l = 3 - match[i] - match[(i + 1) % 3];
      const int s = corner(g, l);
      const Point &a = p(corner(f, i)), &b = p(corner(f, (i + 1) % 3));
      return CGAL::coplanar(a, b, p(r), p(s)) &&
             CGAL::coplanar_orientation(a, b, p(r), p(s)) == CGAL::POSITIVE;
    }
    const Kernel::Triangle_3 tf(p(corner(f, 0)), p(corner(f, 1)), p(corner(f, 2)));
    const Kernel::Triangle_3 tg(p(corner(g, 0)), p(corner(g, 1)), p(corner(g, 2)));
    if (shared == 1) {
      int i = 0;
      while (match[i] < 0)
        ++i;
      const int j = match[i];
      const Kernel::Segment_3 opposite_f(p(corner(f, (i + 1) % 3)), p(corner(f, (i + 2) % 3)));
      const Kernel::Segment_3 opposite_g(p(corner(g, (j + 1) % 3)), p(corner(g, (j + 2) % 3)));
      return CGAL::do_intersect(tf, opposite_g) || CGAL::do_intersect(tg, opposite_f);
    }
    return CGAL::do_intersect(tf, tg);
  };

  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Eigen::Index>;
  std::vector<Box> boxes;
  boxes.reserve(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    boxes.emplace_back(p(corner(f, 0)).bbox() + p(corner(f, 1)).bbox() + p(corner(f, 2)).bbox(),
                       f);
  // The boxes are scanned in slabs across the longest axis of the part, one per thread: a box
  // goes to every slab its extent meets, and a pair of boxes is tested in the one slab that
  // holds the start of their overlap along the axis, max(lo_f, lo_g) (both boxes contain it),
  // so each pair is tested once, whatever the number of slabs.
  const int slabs = static_cast<int>(std::max<Eigen::Index>(
      1, std::min<Eigen::Index>(faces.rows() / kSelfIntersectionSlabFaces, omp_get_max_threads())));
  int axis = 0;
  std::vector<double> cut(static_cast<std::size_t>(slabs) + 1,
                          std::numeric_limits<double>::infinity());
  cut[0] = -std::numeric_limits<double>::infinity();
  if (slabs > 1) {
    Eigen::Array3d lo = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Array3d hi = -lo;
    for (const Box& b : boxes)
      for (int d = 0; d < 3; ++d) {
        lo(d) = std::min(lo(d), b.min_coord(d));
        hi(d) = std::max(hi(d), b.max_coord(d));
      }
    (hi - lo).maxCoeff(&axis);
    // Cuts at quantiles of the boxes' lower ends along the axis: slabs of equal box counts.
    std::vector<double> starts(boxes.size());
    for (std::size_t k = 0; k < boxes.size(); ++k) starts[k] = boxes[k].min_coord(axis);
    for (int s = 1; s < slabs; ++s) {
      const auto at = starts.begin() + static_cast<std::ptrdiff_t>(starts.size() * s / slabs);
      std::nth_element(starts.begin(), at, starts.end());
      cut[static_cast<std::size_t>(s)] = *at;
    }
  }
  std::vector<CgalSelfIntersections> found(static_cast<std::size_t>(slabs));
#pragma omp parallel for schedule(static, 1) num_threads(slabs) if (slabs > 1)
  for (int s = 0; s < slabs; ++s) {
    const double begin = cut[static_cast<std::size_t>(s)], end = cut[static_cast<std::size_t>(s) + 1];
    std::vector<Box> slab;
    if (slabs == 1)
      slab = std::move(boxes);  // the only slab: the scan may reorder the boxes themselves
    else
      for (const Box& b : boxes)
        if (b.min_coord(axis) < end && b.max_coord(axis) >= begin) slab.push_back(b);
    CgalSelfIntersections& out = found[static_cast<std::size_t>(s)];
    // Below 2000 boxes the streaming algorithm compares all pairs, as CGAL's
    // self_intersections does (with the default of 10 it recursed far deeper: 2.6 s instead of
    // 1.2 s on a geodesic sphere of 10⁶ faces).
    constexpr std::ptrdiff_t kBoxCutoff = 2000;
    CGAL::box_self_intersection_d(
        slab.begin(), slab.end(),
        [&](const Box& x, const Box& y) {
          const double start = std::max(x.min_coord(axis), y.min_coord(axis));
          if (start < begin || start >= end)
            return;  // tested in the slab that holds the overlap's start
          const Eigen::Index f = std::min(x.info(), y.info()), g = std::max(x.info(), y.info());
          if (!intersect(f, g))
            return;
          ++out.pairs;
          if (out.list.size() < kMaxListedIntersections)
            out.list.emplace_back(f, g);
        },
        kBoxCutoff);
  }
  for (CgalSelfIntersections& part : found) {
    result.pairs += part.pairs;
    result.list.insert(result.list.end(), part.list.begin(), part.list.end());
  }
  std::sort(result.list.begin(), result.list.end());
  if (result.list.size() > kMaxListedIntersections)
    result.list.resize(kMaxListedIntersections);
  return result;
}

CgalRemeshResult cgal_isotropic_remesh(const Eigen::MatrixX3d& vertices,
                                       const Eigen::MatrixX3i& faces,
                                       const CgalRemeshParameters& parameters) {
  std::vector<Eigen::Index> face_of;
  std::size_t skipped = 0;
  Mesh mesh = to_surface_mesh(vertices, faces, face_of, skipped);
  if (skipped > 0 || !CGAL::is_closed(mesh))
    throw InputError("remeshing needs a closed manifold surface; prepare the mesh first");

  // The input surface, kept for projecting the vertices of the final edge splits.
  std::vector<Kernel::Triangle_3> input_triangles;
  for (FaceIndex f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    input_triangles.emplace_back(mesh.point(mesh.source(h)), mesh.point(mesh.target(h)),
                                 mesh.point(mesh.target(mesh.next(h))));
  }
  using Primitive =
      CGAL::AABB_triangle_primitive<Kernel, std::vector<Kernel::Triangle_3>::const_iterator>;
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>> input_tree(input_triangles.begin(),
                                                                   input_triangles.end());
  input_tree.accelerate_distance_queries();

  CgalRemeshResult result;
  auto sharp = mesh.add_property_map<EdgeIndex, bool>("e:sharp", false).first;
  auto corner = mesh.add_property_map<VertexIndex, bool>("v:corner", false).first;
  auto degree = mesh.add_property_map<VertexIndex, int>("v:sharp_degree", 0).first;
  PMP::detect_sharp_edges(mesh, parameters.sharp_angle_degrees, sharp,
                          CGAL::parameters::vertex_feature_degree_map(degree));
  for (EdgeIndex e : mesh.edges())
    if (sharp[e])
      ++result.sharp_edges;
  // Vertices where sharp polylines end, branch or meet (corners of the part) never move;
  // the polylines themselves are only split, never collapsed or flipped, so they stay
  // exactly where the input had them.
  for (VertexIndex v : mesh.vertices())
    corner[v] = degree[v] != 0 && degree[v] != 2;

  PMP::isotropic_remeshing(mesh.faces(), parameters.target_edge, mesh,
                           CGAL::parameters::number_of_iterations(parameters.iterations)
                               .edge_is_constrained_map(sharp)
                               .vertex_is_constrained_map(corner)
                               .protect_constraints(false)
                               .collapse_constraints(false)
                               .relax_constraints(false));

  // CGAL splits edges longer than 4/3 of the target, so a few edges end up to 1.33× long;
  // split those above max_edge and put the new vertices back onto the input surface.
  mesh.collect_garbage();  // so that the vertices the splits create are appended
  const std::size_t before = mesh.number_of_vertices();
  std::vector<EdgeIndex> edges(mesh.edges().begin(), mesh.edges().end());
  PMP::split_long_edges(edges, parameters.max_edge, mesh,
                        CGAL::parameters::edge_is_constrained_map(sharp));
  for (VertexIndex v : mesh.vertices()) {
    if (static_cast<std::size_t>(v.idx()) < before)
      continue;
    // A vertex on a sharp edge is the midpoint of a straight piece of the input polyline.
    bool on_sharp = false;
    for (auto h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh))
      on_sharp = on_sharp || sharp[mesh.edge(h)];
    if (!on_sharp)
      mesh.point(v) = input_tree.closest_point(mesh.point(v));
  }
  mesh.collect_garbage();
  to_arrays(mesh, result.vertices, result.faces);
  return result;
}

}  // namespace bemshape::geometry::detail
