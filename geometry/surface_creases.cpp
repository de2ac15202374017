#include "geometry/surface_creases.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <unordered_map>

#include "core/errors.hpp"
#include "geometry/bilateral_normals.hpp"

namespace bemshape::geometry {
namespace {

/// A vertex with two creases is inside a straight crease if it lies within this fraction of
/// the bounding-box diagonal of the line through its two crease neighbours (and between
/// them): removing it then moves the surface by no more than that, far below the 1e-9 of the
/// diagonal the remesher promises. Float32 STL coordinates put collinear points up to ~1e-7
/// of the diagonal off their line; those stay corners.
constexpr double kCollinearTolerance = 1e-10;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      auto& p = parent[static_cast<std::size_t>(i)];
      p = parent[static_cast<std::size_t>(p)];
      i = p;
    }
    return i;
  }
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

struct EdgeFaces {
  int a = 0, b = 0;     // vertices, a < b
  int f0 = -1, f1 = -1;  // the two faces
  int count = 0;
  double angle = 0.0;
};

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

}  // namespace

int SurfaceCreases::smoothed_edges() const {
  return static_cast<int>(
      std::count_if(crossed.begin(), crossed.end(), [](const CrossedEdge& e) { return e.smoothed; }));
}

double longest_chord_within(double angle, double facet_width, double chord_tolerance) {
  if (!(angle > 0.0))
    return std::numeric_limits<double>::infinity();
  if (chord_tolerance <= 0.5 * facet_width * angle)
    return 4.0 * chord_tolerance / angle;  // sag = h·θ/4, one facet edge crossed
  return std::sqrt(8.0 * facet_width * chord_tolerance / angle);  // sag = h²θ/(8w)
}

SurfaceCreases find_surface_creases(const SurfaceMesh& mesh, const CreaseOptions& options) {
  const Eigen::MatrixX3i& F = mesh.faces();
  const Eigen::MatrixX3d& V = mesh.vertices();
  const Eigen::MatrixX3d N = options.normal_scale > 0.0
                                 ? bilateral_face_normals(mesh, options.normal_scale)
                                 : mesh.face_normals();
  const int nf = static_cast<int>(F.rows());
  const int nv = static_cast<int>(V.rows());

  // Edges and their two faces.
  std::unordered_map<std::uint64_t, int> index;
  index.reserve(static_cast<std::size_t>(3 * nf / 2 + 1));
  std::vector<EdgeFaces> edges;
  edges.reserve(static_cast<std::size_t>(3 * nf / 2 + 1));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      const auto [it, inserted] = index.try_emplace(edge_key(a, b), static_cast<int>(edges.size()));
      if (inserted)
        edges.push_back({std::min(a, b), std::max(a, b), f, -1, 1, 0.0});
      else {
        EdgeFaces& e = edges[static_cast<std::size_t>(it->second)];
        if (++e.count == 2)
          e.f1 = f;
      }
    }
  for (const EdgeFaces& e : edges)
    if (e.count != 2) {
      std::ostringstream msg;
      msg << "crease detection: the edge from (" << V.row(e.a) << ") to (" << V.row(e.b)
          << ") has " << e.count << " faces; the surface must be closed and manifold (prepare the "
          << "mesh first)";
      throw InputError(msg.str());
    }
  for (EdgeFaces& e : edges) {
    const Eigen::Vector3d n0 = N.row(e.f0), n1 = N.row(e.f1);
    e.angle = std::atan2(n0.cross(n1).norm(), n0.dot(n1));
  }

  const double crease_angle = options.crease_angle_degrees * std::numbers::pi / 180.0;
  const double smooth_angle = options.smooth_angle_degrees * std::numbers::pi / 180.0;
  const bool tessellation = smooth_angle > crease_angle;
  const bool smoothing = tessellation && options.chord_tolerance > 0.0;
  auto candidate = [&](const EdgeFaces& e) { return e.angle > crease_angle; };
  auto small_candidate = [&](const EdgeFaces& e) {
    return e.angle > crease_angle && e.angle <= smooth_angle;
  };

  // Planar facets: faces joined across edges with θ ≤ θ_c.
  UnionFind facets(nf);
  for (const EdgeFaces& e : edges)
    if (!candidate(e))
      facets.unite(e.f0, e.f1);
  std::vector<int> facet_of(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f)
    facet_of[static_cast<std::size_t>(f)] = facets.find(f);

  // Facet areas, the length of their small-angle candidate edges and their distinct
  // neighbours across those.
  std::vector<double> facet_area(static_cast<std::size_t>(nf), 0.0);
  std::vector<double> facet_candidate_length(static_cast<std::size_t>(nf), 0.0);
  std::vector<std::set<int>> facet_neighbours(tessellation ? static_cast<std::size_t>(nf) : 0);
  for (int f = 0; f < nf; ++f)
    facet_area[static_cast<std::size_t>(facet_of[static_cast<std::size_t>(f)])] += mesh.face_areas()(f);
  for (const EdgeFaces& e : edges) {
    if (!small_candidate(e) || !tessellation)
      continue;
    const int A = facet_of[static_cast<std::size_t>(e.f0)], B = facet_of[static_cast<std::size_t>(e.f1)];
    const double length = (V.row(e.a) - V.row(e.b)).norm();
    facet_candidate_length[static_cast<std::size_t>(A)] += length;
    facet_candidate_length[static_cast<std::size_t>(B)] += length;
    facet_neighbours[static_cast<std::size_t>(A)].insert(B);
    facet_neighbours[static_cast<std::size_t>(B)].insert(A);
  }

  SurfaceCreases result;
  result.normals = N;
  std::vector<char> is_crease(edges.size(), 0);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const EdgeFaces& e = edges[i];
    const double length = (V.row(e.a) - V.row(e.b)).norm();
    if (candidate(e)) {
      bool smoothed = false, tessellated = false;
      CrossedEdge crossed{e.a, e.b, e.angle, 0.0, std::numeric_limits<double>::infinity(), false,
                          e.f0, e.f1};
      if (tessellation && small_candidate(e)) {
        const auto A = static_cast<std::size_t>(facet_of[static_cast<std::size_t>(e.f0)]);
        const auto B = static_cast<std::size_t>(facet_of[static_cast<std::size_t>(e.f1)]);
        const bool strip = A != B && (!options.require_facet_strips ||
                                      (facet_neighbours[A].size() >= 2 && facet_neighbours[B].size() >= 2));
        // A candidate inside one facet (its two faces joined around its ends across edges of
        // θ ≤ θ_c) separates nothing: a jump of the filtered normals on a round, a kink that
        // fades out. Without rule 1 it is smoothed like any candidate, at the width between
        // its two faces' centroids, the distance over which the normals turned by θ.
        const bool inside_facet = A == B && !options.require_facet_strips;
        if (strip || inside_facet) {
          tessellated = true;
          crossed.facet_width =
              strip ? std::min(2.0 * facet_area[A] / facet_candidate_length[A],
                               2.0 * facet_area[B] / facet_candidate_length[B])
                    : (mesh.face_centroids().row(e.f0) - mesh.face_centroids().row(e.f1)).norm();
          if (smoothing) {
            crossed.max_chord =
                longest_chord_within(e.angle, crossed.facet_width, options.chord_tolerance);
            smoothed = crossed.max_chord >= options.min_chord;
          }
        }
      }
      if (smoothed) {
        crossed.smoothed = true;
        result.crossed.push_back(crossed);
      } else {
        is_crease[i] = 1;
        result.creases.push_back({e.a, e.b, e.angle, tessellated, crossed.facet_width});
      }
    } else if (e.angle > kCurvedEdgeAngle) {
      // Inside a facet of θ ≤ θ_c: the width across it is the lower face height; with normals
      // filtered at a scale, at least that scale, over which the filtered normals turn however
      // narrow the faces (a CAD export's slivers would otherwise read as a radius of a few
      // hundredths of a millimetre, and ask for elements as small).
      const double width =
          std::max(2.0 * std::min(mesh.face_areas()(e.f0), mesh.face_areas()(e.f1)) /
                       std::max(length, std::numeric_limits<double>::min()),
                   options.normal_scale);
      result.crossed.push_back({e.a, e.b, e.angle, width,
                                options.chord_tolerance > 0.0
                                    ? longest_chord_within(e.angle, width, options.chord_tolerance)
                                    : std::numeric_limits<double>::infinity(),
                                false, e.f0, e.f1});
    }
  }

  // Crease degrees and corners.
  std::vector<std::array<int, 2>> crease_faces(static_cast<std::size_t>(nv), {-1, -1});
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (is_crease[i])
      for (int v : {edges[i].a, edges[i].b})
        crease_faces[static_cast<std::size_t>(v)] = {edges[i].f0, edges[i].f1};
  result.crease_degree = Eigen::VectorXi::Zero(nv);
  std::vector<std::array<int, 2>> crease_neighbours(static_cast<std::size_t>(nv), {-1, -1});
  for (const DihedralEdge& c : result.creases)
    for (const auto& [v, w] : {std::pair{c.a, c.b}, std::pair{c.b, c.a}}) {
      int& degree = result.crease_degree(v);
      if (degree < 2)
        crease_neighbours[static_cast<std::size_t>(v)][static_cast<std::size_t>(degree)] = w;
      ++degree;
    }
  const double tolerance = kCollinearTolerance * mesh.bounding_box().diagonal();
  result.corner.assign(static_cast<std::size_t>(nv), 0);
  result.curved.assign(static_cast<std::size_t>(nv), 0);
  const double curve_turn = options.curve_turn_degrees * std::numbers::pi / 180.0;
  for (int v = 0; v < nv; ++v) {
    const int degree = result.crease_degree(v);
    if (degree == 0)
      continue;
    if (degree != 2) {
      result.corner[static_cast<std::size_t>(v)] = 1;
      continue;
    }
    const Eigen::Vector3d p = V.row(v);
    const Eigen::Vector3d a = V.row(crease_neighbours[static_cast<std::size_t>(v)][0]);
    const Eigen::Vector3d b = V.row(crease_neighbours[static_cast<std::size_t>(v)][1]);
    const Eigen::Vector3d ab = b - a;
    const double t = (p - a).dot(ab) / ab.squaredNorm();
    const double off_line = (p - (a + t * ab)).norm();
    result.corner[static_cast<std::size_t>(v)] = !(t > 0.0 && t < 1.0 && off_line <= tolerance);
  }
  // Curved vertices: corners of degree 2 where the crease turns by at most the curve turn.
  // Their crease's radius ρ is read over a window of arc length on each side (the normal
  // scale, else the two crease edges at the vertex): the turns of the vertices within it over
  // its length. An export's polygon turns at its facets' corners and (to rounding) not at the
  // vertices it adds between them, so the edges at one vertex alone would say nothing.
  if (curve_turn > 0.0) {
    std::vector<double> turn(static_cast<std::size_t>(nv), 0.0);
    for (int v = 0; v < nv; ++v) {
      if (result.crease_degree(v) != 2) continue;
      const auto [na, nb] = crease_neighbours[static_cast<std::size_t>(v)];
      const Eigen::Vector3d in = V.row(v) - V.row(na), out = V.row(nb) - V.row(v);
      turn[static_cast<std::size_t>(v)] = std::atan2(in.cross(out).norm(), in.dot(out));
    }
    // The turn of the vertices from `from` towards `towards` within `window` of arc (up to a
    // vertex where creases branch or end), and the arc they own: the crease up to the last of
    // them and half the edge beyond it, so that a regular polygon reads its own radius.
    auto walk = [&](int from, int towards, double window, double& arc, double& turned) {
      double walked = 0.0;
      int previous = from, current = towards;
      for (int steps = 0; steps < nv; ++steps) {
        const double edge = (V.row(current) - V.row(previous)).norm();
        if (walked + edge > window || result.crease_degree(current) != 2 || current == from) {
          walked += 0.5 * edge;
          break;
        }
        walked += edge;
        turned += turn[static_cast<std::size_t>(current)];
        const auto& next = crease_neighbours[static_cast<std::size_t>(current)];
        const int following = next[0] == previous ? next[1] : next[0];
        previous = current;
        current = following;
      }
      arc += walked;
    };
    for (int v = 0; v < nv; ++v) {
      const double theta = turn[static_cast<std::size_t>(v)];
      if (result.crease_degree(v) != 2 || !result.corner[static_cast<std::size_t>(v)] ||
          !(theta <= curve_turn))
        continue;
      result.curved[static_cast<std::size_t>(v)] = 1;
      const auto [na, nb] = crease_neighbours[static_cast<std::size_t>(v)];
      const double window =
          options.normal_scale > 0.0
              ? options.normal_scale
              : 0.5 * ((V.row(v) - V.row(na)).norm() + (V.row(v) - V.row(nb)).norm());
      double arc = 0.0, turned = theta;
      walk(v, na, window, arc, turned);
      walk(v, nb, window, arc, turned);
      // The chord rule of a facet edge with θ and w = ρ·θ is the arc's sagitta h²/(8ρ).
      const double radius = turned > 0.0 ? arc / turned : std::numeric_limits<double>::infinity();
      const double width = radius * theta;
      const auto [f0, f1] = crease_faces[static_cast<std::size_t>(v)];
      if (theta > kCurvedEdgeAngle)
        result.crossed.push_back({v, v, theta, width,
                                  options.chord_tolerance > 0.0
                                      ? longest_chord_within(theta, width, options.chord_tolerance)
                                      : std::numeric_limits<double>::infinity(),
                                  false, f0, f1});
    }
  }

  // A closed crease loop whose every vertex lies on the line of its neighbours (possible only
  // within the tolerance, for a loop that is tiny against the diagonal) gets one corner, so
  // that every straight crease runs from a corner to a corner.
  std::vector<std::vector<int>> crease_adjacency(static_cast<std::size_t>(nv));
  for (const DihedralEdge& c : result.creases) {
    crease_adjacency[static_cast<std::size_t>(c.a)].push_back(c.b);
    crease_adjacency[static_cast<std::size_t>(c.b)].push_back(c.a);
  }
  std::vector<char> reached(static_cast<std::size_t>(nv), 0);
  for (int v = 0; v < nv; ++v)
    if (result.corner[static_cast<std::size_t>(v)])
      reached[static_cast<std::size_t>(v)] = 1;
  for (int v = 0; v < nv; ++v)
    for (int w : crease_adjacency[static_cast<std::size_t>(v)]) {
      if (!result.corner[static_cast<std::size_t>(v)])
        break;
      // Walk from the corner v through the non-corner vertices.
      int previous = v, current = w;
      while (!result.corner[static_cast<std::size_t>(current)] &&
             !reached[static_cast<std::size_t>(current)]) {
        reached[static_cast<std::size_t>(current)] = 1;
        const auto& next = crease_adjacency[static_cast<std::size_t>(current)];
        const int following = next[0] == previous ? next[1] : next[0];
        previous = current;
        current = following;
      }
    }
  for (int v = 0; v < nv; ++v)
    if (result.crease_degree(v) > 0 && !reached[static_cast<std::size_t>(v)]) {
      result.corner[static_cast<std::size_t>(v)] = 1;  // a loop without corners
      int previous = v, current = crease_adjacency[static_cast<std::size_t>(v)][0];
      reached[static_cast<std::size_t>(v)] = 1;
      while (current != v) {
        reached[static_cast<std::size_t>(current)] = 1;
        const auto& next = crease_adjacency[static_cast<std::size_t>(current)];
        const int following = next[0] == previous ? next[1] : next[0];
        previous = current;
        current = following;
      }
    }

  // Patches: faces joined across non-crease edges.
  UnionFind patches(nf);
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (!is_crease[i])
      patches.unite(edges[i].f0, edges[i].f1);
  result.face_patch.resize(nf);
  std::unordered_map<int, int> patch_number;
  for (int f = 0; f < nf; ++f) {
    const auto [it, inserted] =
        patch_number.try_emplace(patches.find(f), static_cast<int>(patch_number.size()));
    result.face_patch(f) = it->second;
  }
  result.patches = static_cast<int>(patch_number.size());
  return result;
}

}  // namespace bemshape::geometry
