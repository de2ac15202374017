// The translation unit that compiles CGAL's stitching, hole filling and fairing (slow to
// compile; CGAL_EIGEN3_ENABLED is set for it in geometry/CMakeLists.txt so that fairing uses
// Eigen's sparse LU). The union of overlapping bodies uses cgal_boolean_operations.cpp.
#include "geometry/detail/cgal_mesh_repair.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/selection.h>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <exception>
#include <map>
#include <set>

namespace bemshape::geometry::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VertexIndex = Mesh::Vertex_index;
using FaceIndex = Mesh::Face_index;
using HalfedgeIndex = Mesh::Halfedge_index;

Eigen::Vector3d to_eigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

/// Builds a Surface_mesh from the faces listed in `which` (all if empty). False if the faces
/// do not form a manifold, consistently oriented surface (then `mesh` is unusable). With
/// `face_of`, face_of[f.idx()] is the input face of mesh face f.
bool build_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                const std::vector<Eigen::Index>& which, Mesh& mesh,
                std::vector<Eigen::Index>* face_of = nullptr) {
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> polygons;
  std::vector<Eigen::Index> input_face;
  std::map<int, std::size_t> index;
  auto vertex = [&](int v) {
    const auto [it, inserted] = index.try_emplace(v, points.size());
    if (inserted)
      points.emplace_back(vertices(v, 0), vertices(v, 1), vertices(v, 2));
    return it->second;
  };
  auto add = [&](Eigen::Index f) {
    polygons.push_back({vertex(faces(f, 0)), vertex(faces(f, 1)), vertex(faces(f, 2))});
    input_face.push_back(f);
  };
  if (which.empty())
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      add(f);
  else
    for (Eigen::Index f : which)
      add(f);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    return false;
  // In a new mesh, polygon_soup_to_polygon_mesh adds point i as vertex i and polygon i as
  // face i.
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (face_of != nullptr)
    *face_of = input_face;
  return true;
}

void to_arrays(const Mesh& mesh, Eigen::MatrixX3d& vertices, Eigen::MatrixX3i& faces) {
  std::vector<int> index(mesh.num_vertices(), -1);
  vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  int next = 0;
  for (VertexIndex v : mesh.vertices()) {
    vertices.row(next) = to_eigen(mesh.point(v)).transpose();
    index[static_cast<std::size_t>(v.idx())] = next++;
  }
  faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  Eigen::Index f = 0;
  for (FaceIndex fi : mesh.faces()) {
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(fi), mesh))
      if (k < 3)
        faces(f, k++) = index[static_cast<std::size_t>(v.idx())];
    ++f;
  }
}

/// Removes the faces and then every vertex no face uses any more, and compacts the mesh
/// (kept vertices and faces keep their relative order).
void remove_faces(Mesh& mesh, const std::vector<FaceIndex>& faces) {
  for (FaceIndex f : faces)
    CGAL::Euler::remove_face(mesh.halfedge(f), mesh);
  for (VertexIndex v : mesh.vertices())
    if (mesh.is_isolated(v))
      mesh.remove_vertex(v);
  mesh.collect_garbage();
}

CgalHole measure_loop(const Mesh& mesh, HalfedgeIndex h) {
  CgalHole hole;
  std::vector<Eigen::Vector3d> points;
  for (HalfedgeIndex g : CGAL::halfedges_around_face(h, mesh))
    points.push_back(to_eigen(mesh.point(mesh.target(g))));
  hole.edges = points.size();
  Eigen::Vector3d lo = points[0], hi = points[0], sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    sum += p;
  }
  hole.extent = (hi - lo).norm();
  hole.centre = sum / static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points)
    covariance += (p - hole.centre) * (p - hole.centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Vector3d normal = eigen.eigenvectors().col(0);  // smallest eigenvalue
  for (const Eigen::Vector3d& p : points)
    hole.out_of_plane = std::max(hole.out_of_plane, std::abs((p - hole.centre).dot(normal)));
  return hole;
}

/// Fills the hole bounded by the border halfedge h; measures it first.
CgalHole fill(Mesh& mesh, HalfedgeIndex h) {
  CgalHole hole = measure_loop(mesh, h);
  std::vector<FaceIndex> patch;
  std::vector<VertexIndex> added;
  try {
    const auto result = PMP::triangulate_refine_and_fair_hole(
        mesh, h, std::back_inserter(patch), std::back_inserter(added));
    hole.faired = std::get<0>(result);
  } catch (const std::exception&) {
    // A CGAL failure inside the filling leaves the hole open; the caller refuses it.
    patch.clear();
  }
  hole.filled = !patch.empty();
  hole.faces_added = patch.size();
  for (FaceIndex f : patch)
    hole.area_added += PMP::face_area(f, mesh);
  return hole;
}

}  // namespace

CgalHoleClosing cgal_close_holes(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                 double max_piece_extent, double max_hole_extent,
                                 std::size_t max_hole_edges) {
  CgalHoleClosing result;
  Mesh mesh;
  if (!build_mesh(vertices, faces, {}, mesh)) {
    result.vertices = vertices;
    result.faces = faces;
    return result;
  }
  result.edges_stitched = PMP::stitch_borders(mesh);
  mesh.collect_garbage();

  // Loose open pieces.
  auto component = mesh.add_property_map<FaceIndex, std::size_t>("f:component", 0).first;
  const std::size_t components = PMP::connected_components(mesh, component);
  std::vector<char> has_border(components, 0);
  std::vector<CGAL::Bbox_3> box(components);
  std::vector<CgalLoosePiece> piece(components);
  for (FaceIndex f : mesh.faces()) {
    const std::size_t c = component[f];
    for (HalfedgeIndex h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) {
      box[c] += mesh.point(mesh.target(h)).bbox();
      if (mesh.is_border(mesh.opposite(h)))
        has_border[c] = 1;
    }
    ++piece[c].faces;
    piece[c].area += PMP::face_area(f, mesh);
  }
  std::vector<FaceIndex> loose;
  for (std::size_t c = 0; c < components; ++c) {
    const Eigen::Vector3d lo(box[c].xmin(), box[c].ymin(), box[c].zmin());
    const Eigen::Vector3d hi(box[c].xmax(), box[c].ymax(), box[c].zmax());
    piece[c].extent = (hi - lo).norm();
    piece[c].where = 0.5 * (lo + hi);
    if (has_border[c] && piece[c].extent <= max_piece_extent)
      result.pieces_removed.push_back(piece[c]);
  }
  for (FaceIndex f : mesh.faces()) {
    const std::size_t c = component[f];
    if (has_border[c] && piece[c].extent <= max_piece_extent)
      loose.push_back(f);
  }
  mesh.remove_property_map(component);
  if (!loose.empty())
    remove_faces(mesh, loose);

  // Holes.
  std::vector<HalfedgeIndex> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  for (HalfedgeIndex h : cycles) {
    const CgalHole measured = measure_loop(mesh, h);
    if (measured.extent <= max_hole_extent && measured.edges <= max_hole_edges)
      result.holes.push_back(fill(mesh, h));
    else
      result.holes.push_back(measured);
  }
  to_arrays(mesh, result.vertices, result.faces);
  return result;
}

CgalFaceReplacement cgal_replace_faces(const Eigen::MatrixX3d& vertices,
                                       const Eigen::MatrixX3i& faces,
                                       const std::vector<char>& remove) {
  CgalFaceReplacement result;
  Mesh mesh;
  std::vector<Eigen::Index> face_of;
  if (!build_mesh(vertices, faces, {}, mesh, &face_of)) {
    result.vertices = vertices;
    result.faces = faces;
    result.all_filled = false;
    return result;
  }
  std::vector<FaceIndex> selected;
  for (FaceIndex f : mesh.faces()) {
    const Eigen::Index input = face_of[f.idx()];
    if (input >= 0 && remove[static_cast<std::size_t>(input)])
      selected.push_back(f);
  }
  auto is_selected = mesh.add_property_map<FaceIndex, bool>("f:selected", false).first;
  for (FaceIndex f : selected)
    is_selected[f] = true;
  CGAL::expand_face_selection_for_removal(selected, mesh, is_selected);
  std::vector<FaceIndex> removing;
  for (FaceIndex f : mesh.faces())
    if (is_selected[f])
      removing.push_back(f);
  mesh.remove_property_map(is_selected);
  result.faces_removed = removing.size();

  // The loops that exist before the removal are not this function's to fill.
  std::vector<HalfedgeIndex> before;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(before));
  std::set<std::pair<int, int>> old_border;
  for (HalfedgeIndex h : before)
    for (HalfedgeIndex g : CGAL::halfedges_around_face(h, mesh))
      old_border.insert({static_cast<int>(mesh.source(g).idx()),
                         static_cast<int>(mesh.target(g).idx())});
  // Vertex indices survive collect_garbage only in relative order; remember positions.
  std::set<std::array<double, 6>> old_edges;
  for (const auto& [s, t] : old_border) {
    const Point& a = mesh.point(VertexIndex(static_cast<Mesh::size_type>(s)));
    const Point& b = mesh.point(VertexIndex(static_cast<Mesh::size_type>(t)));
    old_edges.insert({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()});
  }
  remove_faces(mesh, removing);

  std::vector<HalfedgeIndex> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  for (HalfedgeIndex h : cycles) {
    const Point& a = mesh.point(mesh.source(h));
    const Point& b = mesh.point(mesh.target(h));
    if (old_edges.count({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}) != 0)
      continue;
    result.holes.push_back(fill(mesh, h));
    result.all_filled = result.all_filled && result.holes.back().filled;
  }
  to_arrays(mesh, result.vertices, result.faces);
  return result;
}

}  // namespace bemshape::geometry::detail
