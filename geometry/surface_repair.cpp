#include "geometry/surface_repair.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>
#include <array>
#include <cstdio>
#include <map>
#include <numeric>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/detail/cgal_mesh_repair.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/nonmanifold_split.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/union_find.hpp"
#include "geometry/winding_number_boundary.hpp"

namespace bemshape::geometry {
namespace {

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

std::string point(const Eigen::Vector3d& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buffer;
}

std::string counted(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

/// Signed volume (1/6) Σ a·(b×c) of the faces (all, or those with keep[f]).
double signed_volume(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                     const std::vector<char>* keep = nullptr) {
  double volume = 0.0;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (keep == nullptr || (*keep)[static_cast<std::size_t>(i)])
      volume += Eigen::Vector3d(v.row(f(i, 0)))
                    .dot(Eigen::Vector3d(v.row(f(i, 1))).cross(Eigen::Vector3d(v.row(f(i, 2)))));
  return volume / 6.0;
}

/// Bounding box of the vertices of the faces with in[f].
Eigen::AlignedBox3d box_of(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                           const std::vector<char>& in) {
  Eigen::AlignedBox3d box;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (in[static_cast<std::size_t>(i)])
      for (int k = 0; k < 3; ++k)
        box.extend(Eigen::Vector3d(v.row(f(i, k))));
  return box;
}

/// Adds to `in` every face with allowed[f] sharing a vertex with it, `rings` times.
void grow(const Eigen::MatrixX3i& f, std::size_t num_vertices, const std::vector<char>& allowed,
          std::vector<char>& in, int rings) {
  for (int r = 0; r < rings; ++r) {
    std::vector<char> touched(num_vertices, 0);
    for (Eigen::Index i = 0; i < f.rows(); ++i)
      if (in[static_cast<std::size_t>(i)])
        for (int k = 0; k < 3; ++k)
          touched[static_cast<std::size_t>(f(i, k))] = 1;
    for (Eigen::Index i = 0; i < f.rows(); ++i)
      for (int k = 0; k < 3; ++k)
        if (touched[static_cast<std::size_t>(f(i, k))] && allowed[static_cast<std::size_t>(i)])
          in[static_cast<std::size_t>(i)] = 1;
  }
}

/// small[f]: face f is at most `length` across (bounding-box diagonal).
std::vector<char> small_faces(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                              double length) {
  std::vector<char> small(static_cast<std::size_t>(f.rows()), 0);
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 3; ++k)
      box.extend(Eigen::Vector3d(v.row(f(i, k))));
    small[static_cast<std::size_t>(i)] = box.diagonal().norm() <= length;
  }
  return small;
}

struct UnitedShells {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  bool ok = true;
  std::string failure;
};

/// The faces with in[f] with their own compact vertex array.
SurfaceMesh faces_mesh(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                       const std::vector<char>& in) {
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  std::vector<Eigen::Index> rows;
  int next = 0;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (in[static_cast<std::size_t>(i)]) {
      rows.push_back(i);
      for (int k = 0; k < 3; ++k)
        if (index[static_cast<std::size_t>(f(i, k))] < 0)
          index[static_cast<std::size_t>(f(i, k))] = next++;
    }
  Eigen::MatrixX3d vertices(next, 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (index[static_cast<std::size_t>(i)] >= 0)
      vertices.row(index[static_cast<std::size_t>(i)]) = v.row(i);
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (int k = 0; k < 3; ++k)
      faces(static_cast<Eigen::Index>(r), k) =
          index[static_cast<std::size_t>(f(rows[r], k))];
  return SurfaceMesh(std::move(vertices), std::move(faces));
}

/// The faces of one shell with their own compact vertex array.
SurfaceMesh shell_mesh(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                       const std::vector<int>& shell, int which) {
  std::vector<char> in(static_cast<std::size_t>(f.rows()), 0);
  for (std::size_t i = 0; i < in.size(); ++i)
    in[i] = shell[i] == which;
  return faces_mesh(v, f, in);
}

/// The faces with keep[f] on their own vertices, then each replacement with its own.
void assemble(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f, const std::vector<char>& keep,
              const std::vector<SurfaceMesh>& replacements, Eigen::MatrixX3d& vertices,
              Eigen::MatrixX3i& faces) {
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    if (!keep[static_cast<std::size_t>(i)])
      continue;
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      int& at = index[static_cast<std::size_t>(f(i, k))];
      if (at < 0) {
        at = static_cast<int>(points.size());
        points.push_back(v.row(f(i, k)).transpose());
      }
      t[static_cast<std::size_t>(k)] = at;
    }
    triangles.push_back(t);
  }
  for (const SurfaceMesh& mesh : replacements) {
    const int offset = static_cast<int>(points.size());
    for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i)
      points.push_back(mesh.vertices().row(i).transpose());
    for (Eigen::Index i = 0; i < mesh.num_faces(); ++i)
      triangles.push_back({mesh.faces()(i, 0) + offset, mesh.faces()(i, 1) + offset,
                           mesh.faces()(i, 2) + offset});
  }
  vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    vertices.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      faces(static_cast<Eigen::Index>(i), k) = triangles[i][static_cast<std::size_t>(k)];
}

/// Replaces the shells of each group (group[s] for shell s, −1: none) by the boundary of
/// their union (mesh_union: CGAL corefinement, exact predicates and constructions,
/// intersection points rounded to double), each shell oriented outward first. Every shell
/// must be closed and must not cross itself (corefinement's precondition, tested here).
UnitedShells unite_shells(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                          const std::vector<int>& shell, const std::vector<int>& group,
                          const std::vector<std::vector<int>>& members) {
  UnitedShells result;
  std::vector<SurfaceMesh> united;
  for (const std::vector<int>& m : members) {
    SurfaceMesh accumulated;
    for (int s : m) {
      SurfaceMesh body = shell_mesh(v, f, shell, s);
      if (find_self_intersections(body.vertices(), body.faces()).pairs > 0) {
        result.ok = false;
        result.failure = "a shell of the overlapping bodies crosses itself";
        return result;
      }
      if (body.signed_volume() < 0.0)
        body = with_flipped_orientation(body);
      try {
        accumulated = accumulated.empty() ? std::move(body) : mesh_union(accumulated, body);
      } catch (const InputError& e) {
        result.ok = false;
        result.failure = e.what();
        return result;
      }
    }
    united.push_back(std::move(accumulated));
  }
  // Faces of shells in no group keep their vertices; the unions' vertices follow.
  std::vector<char> keep(static_cast<std::size_t>(f.rows()), 0);
  for (std::size_t i = 0; i < keep.size(); ++i)
    keep[i] = group[static_cast<std::size_t>(shell[i])] < 0;
  assemble(v, f, keep, united, result.vertices, result.faces);
  return result;
}

std::string describe_fill(const detail::CgalHole& hole) {
  return "filled a hole of " + counted(hole.edges, "edge", "edges") + ", " +
         number(hole.extent) + " across, at " + point(hole.centre) + " with " +
         counted(hole.faces_added, "triangle", "triangles") + " (area " +
         number(hole.area_added) + "; rim flat to " + number(hole.out_of_plane) +
         (hole.faired ? "" : "; fairing failed, minimal-area patch kept") + ")";
}

Eigen::AlignedBox3d face_box(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                             Eigen::Index face) {
  Eigen::AlignedBox3d b;
  for (int k = 0; k < 3; ++k)
    b.extend(Eigen::Vector3d(v.row(f(face, k))));
  return b;
}

/// Regions listed separately at most; beyond, a surface crosses itself all over and one
/// region holds every crossing (merging is quadratic in the number of regions).
constexpr std::size_t kMaxDefectZones = 256;

/// What was found about a group of crossing shells that the winding numbers did not
/// resolve: where (the curves and the irregular pieces) and why.
struct WindingNote {
  Eigen::AlignedBox3d box;
  std::string why;
};

/// Replaces every group of shells joined by the crossing pairs of `current` (with a pair
/// within one shell, if `self_crossing_only`) by the boundary of the region it encloses,
/// when that is the solid it was meant to bound (no volume of negative winding number);
/// notes why the others were not. True if anything was replaced.
bool resolve_by_winding(IntersectionRepair& result, const SelfIntersections& current,
                        bool self_crossing_only, std::vector<WindingNote>& notes) {
  const Eigen::MatrixX3d& V = result.vertices;
  const Eigen::MatrixX3i& F = result.faces;
  std::size_t shells = 0;
  const std::vector<int> shell = shell_labels(F, &shells);
  UnionFind groups(shells);
  for (const auto& [f, g] : current.face_pairs)
    groups.unite(shell[static_cast<std::size_t>(f)], shell[static_cast<std::size_t>(g)]);
  std::vector<char> crossing(shells, 0), self_crossing(shells, 0);
  std::vector<std::size_t> pairs(shells, 0);
  for (const auto& [f, g] : current.face_pairs) {
    const int root = groups.find(shell[static_cast<std::size_t>(f)]);
    crossing[static_cast<std::size_t>(root)] = 1;
    ++pairs[static_cast<std::size_t>(root)];
    if (shell[static_cast<std::size_t>(f)] == shell[static_cast<std::size_t>(g)])
      self_crossing[static_cast<std::size_t>(root)] = 1;
  }
  std::vector<char> keep(static_cast<std::size_t>(F.rows()), 1);
  std::vector<SurfaceMesh> replacements;
  for (std::size_t root = 0; root < shells; ++root) {
    if (!crossing[root] || (self_crossing_only && !self_crossing[root]))
      continue;
    std::vector<char> in(static_cast<std::size_t>(F.rows()), 0);
    for (std::size_t f = 0; f < in.size(); ++f)
      in[f] = static_cast<std::size_t>(groups.find(shell[f])) == root;
    SurfaceMesh group = faces_mesh(V, F, in);
    // A group whose surface encloses negative volume as a whole (a cavity wall) is resolved
    // turned outward and turned back.
    const bool inward = group.signed_volume() < 0.0;
    if (inward)
      group = with_flipped_orientation(group);
    const WindingNumberBoundary b = winding_number_boundary(group.vertices(), group.faces());
    WindingNote note;
    note.box = b.curves;
    note.box.extend(b.irregular);
    if (note.box.isEmpty())
      for (std::size_t f = 0; f < in.size(); ++f)
        if (in[f])
          note.box.extend(face_box(V, F, static_cast<Eigen::Index>(f)));
    if (!b.ok) {
      note.why = "splitting it along the curves where it crosses itself failed (" + b.failure + ")";
      notes.push_back(std::move(note));
      continue;
    }
    if (b.negative_volume >
            kInsideOutShare * b.overlap_volume + kRoundingVolume * std::max(b.volume, 0.0) ||
        b.faces.rows() == 0) {
      note.why = "the surface is inside out over a region of volume " +
                 number(b.negative_volume) + " (winding number " +
                 std::to_string(b.min_winding) + " there" +
                 (b.overlap_volume > 0.0
                      ? ", beside an overlap of " + number(b.overlap_volume)
                      : ": a fold, or a patch pushed through the opposite wall") +
                 "), so the solid it was meant to bound cannot be told";
      notes.push_back(std::move(note));
      continue;
    }
    // Where the enclosed region touches itself along a curve, four faces meet at an edge:
    // split it apart as at any non-manifold edge.
    const NonmanifoldSplit split = split_nonmanifold(b.vertices, b.faces);
    const MeshValidation valid = validate_mesh(split.vertices, split.faces);
    if (!valid.closed_manifold() || !split.crossing_edges.empty()) {
      note.why = "the boundary of the region it encloses is not a closed manifold surface";
      notes.push_back(std::move(note));
      continue;
    }
    SurfaceMesh resolved(split.vertices, split.faces);
    if (inward)
      resolved = with_flipped_orientation(resolved);
    const double sign = inward ? -1.0 : 1.0;
    SurfaceRepairStep step;
    step.where = note.box.center();
    step.size = note.box.diagonal().norm();
    step.faces_removed = static_cast<std::size_t>(group.num_faces());
    step.faces_added = static_cast<std::size_t>(resolved.num_faces());
    step.description =
        "split the surface along the curves where it crosses itself (" +
        counted(pairs[root], "intersecting pair", "intersecting pairs") + ", " +
        counted(b.faces_split, "face", "faces") + " cut), around " + point(step.where) + ", " +
        number(step.size) + " across, and kept the boundary of the region it encloses (" +
        counted(step.faces_removed, "face", "faces") + " replaced by " +
        std::to_string(step.faces_added) + "): volume " + number(sign * b.signed_volume) +
        " as given (the overlap of " + number(b.overlap_volume) + " counted twice), " +
        number(sign * b.volume) + " after";
    result.crossings_resolved.push_back(std::move(step));
    result.resolved_volume_before += sign * b.signed_volume;
    result.resolved_volume_after += sign * b.volume;
    for (std::size_t f = 0; f < in.size(); ++f)
      keep[f] = keep[f] && !in[f];
    replacements.push_back(std::move(resolved));
  }
  if (replacements.empty())
    return false;
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  assemble(V, F, keep, replacements, vertices, faces);
  result.vertices = std::move(vertices);
  result.faces = std::move(faces);
  return true;
}

/// The regions `left` still crossing: clusters of faces joined by its pairs, each boxed by
/// the intersections of its pairs' face boxes (where their crossing segments lie), grown to
/// the notes' regions it meets and merged where the boxes meet; and the region of the edges
/// along which bodies still pass through each other.
std::vector<DefectZone> unresolved_zones(
    const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const SelfIntersections& left,
    const std::vector<WindingNote>& notes, const std::string& why_left, bool crossings_left,
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& crossing_edges) {
  struct Region {
    Eigen::AlignedBox3d box;
    std::size_t pairs = 0;
    std::string why;
  };
  std::vector<Region> regions;
  if (!left.face_pairs.empty()) {
    UnionFind clusters(static_cast<std::size_t>(F.rows()));
    for (const auto& [f, g] : left.face_pairs)
      clusters.unite(static_cast<int>(f), static_cast<int>(g));
    std::map<int, Region> by_root;
    for (const auto& [f, g] : left.face_pairs) {
      Region& r = by_root[clusters.find(static_cast<int>(f))];
      r.box.extend(face_box(V, F, f).intersection(face_box(V, F, g)));
      ++r.pairs;
    }
    for (auto& [root, r] : by_root)
      regions.push_back(std::move(r));
    // Pairs beyond those listed (a million) belong to the regions found.
    if (left.pairs > left.face_pairs.size())
      regions.front().pairs += left.pairs - left.face_pairs.size();
  }
  if (crossings_left && !crossing_edges.empty()) {
    Region r;
    for (const auto& [a, b] : crossing_edges) {
      r.box.extend(a);
      r.box.extend(b);
    }
    r.why = why_left;
    regions.push_back(std::move(r));
  }
  for (Region& r : regions)
    for (const WindingNote& note : notes)
      if (note.box.intersects(r.box)) {
        r.box.extend(note.box);
        if (r.why.empty())
          r.why = note.why;
      }
  // Merge regions whose boxes meet, until none do; beyond kMaxDefectZones regions (a surface
  // crossing itself all over) one region holds them all.
  if (regions.size() > kMaxDefectZones) {
    for (std::size_t i = 1; i < regions.size(); ++i) {
      regions.front().box.extend(regions[i].box);
      regions.front().pairs += regions[i].pairs;
      if (regions.front().why.empty())
        regions.front().why = regions[i].why;
    }
    regions.resize(1);
  }
  for (bool merged = true; merged;) {
    merged = false;
    UnionFind meeting(regions.size());
    for (std::size_t i = 0; i < regions.size(); ++i)
      for (std::size_t j = i + 1; j < regions.size(); ++j)
        if (regions[i].box.intersects(regions[j].box)) {
          meeting.unite(static_cast<int>(j), static_cast<int>(i));
          merged = true;
        }
    if (!merged)
      break;
    std::map<int, Region> by_root;
    for (std::size_t i = 0; i < regions.size(); ++i) {
      Region& into = by_root[meeting.find(static_cast<int>(i))];
      into.box.extend(regions[i].box);
      into.pairs += regions[i].pairs;
      if (into.why.empty())
        into.why = regions[i].why;
    }
    regions.clear();
    for (auto& [root, r] : by_root)
      regions.push_back(std::move(r));
  }
  std::vector<DefectZone> zones;
  for (const Region& r : regions) {
    DefectZone zone;
    zone.what = r.pairs > 0 ? "the surface crosses itself"
                            : "bodies pass through each other along edges they share";
    zone.why = r.why.empty() ? why_left : r.why;
    zone.box.min = r.box.min();
    zone.box.max = r.box.max();
    zone.pairs = r.pairs;
    zones.push_back(std::move(zone));
  }
  std::sort(zones.begin(), zones.end(),
            [](const DefectZone& a, const DefectZone& b) { return a.size() > b.size(); });
  return zones;
}

}  // namespace

HoleClosing close_small_holes(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                              double repair_length) {
  const detail::CgalHoleClosing closed =
      detail::cgal_close_holes(vertices, faces, repair_length, repair_length, kMaxHoleEdges);
  HoleClosing result;
  result.vertices = closed.vertices;
  result.faces = closed.faces;
  result.edges_stitched = closed.edges_stitched;
  for (const detail::CgalLoosePiece& piece : closed.pieces_removed) {
    SurfaceRepairStep step;
    step.where = piece.where;
    step.size = piece.extent;
    step.faces_removed = piece.faces;
    step.description = "removed a loose open piece of " +
                       counted(piece.faces, "face", "faces") + ", " + number(piece.extent) +
                       " across, at " + point(piece.where) + " (area " + number(piece.area) +
                       "): no solid can be made of it";
    result.pieces_removed.push_back(std::move(step));
  }
  for (const detail::CgalHole& hole : closed.holes) {
    if (hole.filled) {
      SurfaceRepairStep step;
      step.where = hole.centre;
      step.size = hole.extent;
      step.faces_added = hole.faces_added;
      step.description = describe_fill(hole);
      result.holes_filled.push_back(std::move(step));
      continue;
    }
    if (result.holes_left++ == 0) {
      result.first_left = hole.centre;
      result.why_left = hole.extent > repair_length
                            ? "larger than the repair length"
                        : hole.edges > kMaxHoleEdges
                            ? "more than " + std::to_string(kMaxHoleEdges) +
                                  " edges, too many to triangulate"
                            : "CGAL could not triangulate it";
    }
    result.edges_left += hole.edges;
    result.largest_left = std::max(result.largest_left, hole.extent);
  }
  return result;
}

SharedFaceUnion unite_bodies_sharing_faces(const Eigen::MatrixX3d& vertices,
                                           const Eigen::MatrixX3i& faces) {
  SharedFaceUnion result;
  // Duplicates (the same three vertices, either order): sorted keys side by side, so that a
  // part without any, nearly every part, costs one sort.
  std::vector<std::array<int, 3>> keys(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<int, 3> key{faces(f, 0), faces(f, 1), faces(f, 2)};
    if (key[0] == key[1] || key[1] == key[2] || key[0] == key[2])
      return result;
    std::sort(key.begin(), key.end());
    keys[static_cast<std::size_t>(f)] = key;
  }
  std::sort(keys.begin(), keys.end());
  if (std::adjacent_find(keys.begin(), keys.end()) == keys.end())
    return result;
  // The chain's closure: every edge used as often in each direction.
  std::map<std::pair<int, int>, int> net;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      net[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  for (const auto& [edge, count] : net)
    if (count != 0)
      return result;
  // Faces on each other need no splitting (CGAL's autorefinement refuses edges of four
  // faces); should the bodies also cross, the result crosses itself and the later stages
  // find it.
  const WindingNumberBoundary b = winding_number_boundary(vertices, faces, false);
  if (!b.ok || b.faces.rows() == 0 ||
      b.negative_volume >
          kInsideOutShare * b.overlap_volume + kRoundingVolume * std::max(b.volume, 0.0))
    return result;
  const NonmanifoldSplit split = split_nonmanifold(b.vertices, b.faces);
  if (!validate_mesh(split.vertices, split.faces).closed_manifold() ||
      !split.crossing_edges.empty())
    return result;
  Eigen::AlignedBox3d box = b.irregular;
  if (box.isEmpty())
    for (Eigen::Index i = 0; i < vertices.rows(); ++i)
      box.extend(vertices.row(i).transpose());
  result.vertices = split.vertices;
  result.faces = split.faces;
  result.ok = true;
  result.step.where = box.center();
  result.step.size = box.diagonal().norm();
  result.step.faces_removed = static_cast<std::size_t>(faces.rows());
  result.step.faces_added = static_cast<std::size_t>(split.faces.rows());
  result.step.description =
      "united bodies sharing faces (the same triangles in both) into the boundary of the "
      "region they enclose, around " + point(result.step.where) + ", " +
      number(result.step.size) + " across (" +
      counted(result.step.faces_removed, "face", "faces") + " replaced by " +
      std::to_string(result.step.faces_added) + "): volume " + number(b.signed_volume) +
      " as given (the overlap of " + number(b.overlap_volume) + " counted twice), " +
      number(b.volume) + " after";
  return result;
}

IntersectionRepair resolve_self_intersections(
    const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
    const SelfIntersections& found, double repair_length,
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& crossing_edges) {
  IntersectionRepair result;
  result.vertices = vertices;
  result.faces = faces;
  SelfIntersections current = found;
  {
    const std::vector<int> shell = shell_labels(faces);
    for (const auto& [f, g] : found.face_pairs)
      ++(shell[static_cast<std::size_t>(f)] == shell[static_cast<std::size_t>(g)]
             ? result.pairs_within_shells
             : result.pairs_between_shells);
  }
  // Shells crossing themselves first, whatever the size of the crossing, when the solid they
  // bound is clear.
  std::vector<WindingNote> notes;
  bool winding_tried_all = false;
  if (current.pairs > 0 && current.pairs <= current.face_pairs.size() &&
      resolve_by_winding(result, current, true, notes))
    current = find_self_intersections(result.vertices, result.faces);
  int ring = 0;
  int union_rounds = 0;
  bool crossings_pending = !crossing_edges.empty();
  while (current.pairs > 0 || crossings_pending) {
    if (current.pairs > current.face_pairs.size()) {
      result.why_left = "too many intersecting pairs to repair";
      break;
    }
    const Eigen::MatrixX3d& V = result.vertices;
    const Eigen::MatrixX3i& F = result.faces;
    const auto nf = static_cast<std::size_t>(F.rows());
    const std::vector<int> shell = shell_labels(F);
    std::vector<std::pair<Eigen::Index, Eigen::Index>> local, across;
    for (const auto& pair : current.face_pairs)
      (shell[static_cast<std::size_t>(pair.first)] == shell[static_cast<std::size_t>(pair.second)]
           ? local
           : across)
          .push_back(pair);

    if (!local.empty()) {
      if (ring > kMaxIntersectionRings) {
        result.why_left = "cutting out up to " + std::to_string(kMaxIntersectionRings) +
                          " rings of faces around them and refilling did not clear them";
        break;
      }
      // Clusters: faces joined by intersecting pairs.
      UnionFind clusters(nf);
      std::vector<char> involved(nf, 0);
      for (const auto& [f, g] : local) {
        clusters.unite(static_cast<int>(f), static_cast<int>(g));
        involved[static_cast<std::size_t>(f)] = involved[static_cast<std::size_t>(g)] = 1;
      }
      std::vector<int> roots;
      for (std::size_t f = 0; f < nf; ++f)
        if (involved[f]) {
          const int root = clusters.find(static_cast<int>(f));
          if (std::find(roots.begin(), roots.end(), root) == roots.end())
            roots.push_back(root);
        }
      // Only faces at most ℓ across are cut out: a fold or a vertex pushed through a large
      // flat face is cleared by replacing the small faces, the large face stays.
      const std::vector<char> small = small_faces(V, F, repair_length);
      std::vector<char> remove(nf, 0);
      std::vector<SurfaceRepairStep> steps;
      double largest = 0.0;
      Eigen::Vector3d largest_at = Eigen::Vector3d::Zero();
      std::size_t whole_shells = 0;
      for (int root : roots) {
        std::vector<char> region(nf, 0);
        std::size_t pairs = 0;
        std::vector<char> cluster(nf, 0);
        for (std::size_t f = 0; f < nf; ++f) {
          cluster[f] = involved[f] && clusters.find(static_cast<int>(f)) == root;
          region[f] = cluster[f] && small[f];
        }
        for (const auto& pair : local)
          pairs += cluster[static_cast<std::size_t>(pair.first)] ? 1 : 0;
        grow(F, static_cast<std::size_t>(V.rows()), small, region, ring);
        // Cutting out a whole shell would delete a body, not repair it.
        const int own_shell = shell[static_cast<std::size_t>(root)];
        bool whole_shell = true;
        for (std::size_t f = 0; f < nf && whole_shell; ++f)
          whole_shell = shell[f] != own_shell || region[f];
        const bool empty =
            whole_shell || std::find(region.begin(), region.end(), 1) == region.end();
        const Eigen::AlignedBox3d box = box_of(V, F, empty ? cluster : region);
        const double size = box.diagonal().norm();
        if (empty || size > repair_length) {
          whole_shells += whole_shell ? 1 : 0;
          if (size > largest) {
            largest = size;
            largest_at = box.center();
          }
          continue;
        }
        SurfaceRepairStep step;
        step.where = box.center();
        step.size = size;
        step.faces_removed = static_cast<std::size_t>(std::count(region.begin(), region.end(), 1));
        step.description = "cut out " + counted(step.faces_removed, "face", "faces") + " with " +
                           counted(pairs, "intersecting pair", "intersecting pairs") + ", " +
                           number(size) + " across, at " + point(step.where) +
                           ", and refilled the hole";
        steps.push_back(std::move(step));
        for (std::size_t f = 0; f < nf; ++f)
          remove[f] = remove[f] || region[f];
      }
      if (steps.empty()) {
        result.why_left =
            whole_shells > 0
                ? "a shell crosses itself throughout (" + number(largest) + " across at " +
                      point(largest_at) + "): cutting out its crossing faces would delete it"
                : "the surface crosses itself over a region " + number(largest) + " across at " +
                      point(largest_at) + ", larger than the repair length";
        break;
      }
      const double before = signed_volume(V, F);
      detail::CgalFaceReplacement replaced = detail::cgal_replace_faces(V, F, remove);
      ++ring;
      if (!replaced.all_filled)
        continue;  // keep the mesh as it was; the next attempt cuts a ring more
      std::size_t added = 0;
      for (const detail::CgalHole& hole : replaced.holes)
        added += hole.faces_added;
      for (SurfaceRepairStep& step : steps) {
        if (steps.size() == 1) {
          step.faces_added = added;
          step.description += " with " + counted(added, "triangle", "triangles");
        }
        result.clusters_replaced.push_back(std::move(step));
      }
      result.vertices = std::move(replaced.vertices);
      result.faces = std::move(replaced.faces);
      result.volume_change += signed_volume(result.vertices, result.faces) - before;
    } else {
      if (union_rounds++ > 0) {
        result.why_left = "the union of the overlapping bodies still crosses itself";
        break;
      }
      // Bodies: shells joined by crossing pairs; each must have one orientation with the
      // others of its group.
      int shells = 0;
      for (int s : shell)
        shells = std::max(shells, s + 1);
      UnionFind bodies(static_cast<std::size_t>(shells));
      for (const auto& [f, g] : across)
        bodies.unite(shell[static_cast<std::size_t>(f)], shell[static_cast<std::size_t>(g)]);
      // Bodies crossing along an edge they share (welded there, so no face pair intersects):
      // every face with an edge at the same two positions belongs to one of them.
      if (crossings_pending) {
        std::map<std::array<double, 6>, std::vector<Eigen::Index>> faces_at;
        auto key = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
          std::array<double, 6> k{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()};
          if (std::lexicographical_compare(k.begin() + 3, k.end(), k.begin(), k.begin() + 3))
            k = {b.x(), b.y(), b.z(), a.x(), a.y(), a.z()};
          return k;
        };
        for (Eigen::Index f = 0; f < F.rows(); ++f)
          for (int k = 0; k < 3; ++k)
            faces_at[key(V.row(F(f, k)), V.row(F(f, (k + 1) % 3)))].push_back(f);
        for (const auto& [a, b] : crossing_edges) {
          const auto it = faces_at.find(key(a, b));
          if (it == faces_at.end())
            continue;
          for (Eigen::Index f : it->second) {
            bodies.unite(shell[static_cast<std::size_t>(f)],
                         shell[static_cast<std::size_t>(it->second.front())]);
            across.emplace_back(it->second.front(), f);
          }
        }
        crossings_pending = false;
      }
      std::vector<double> volume(static_cast<std::size_t>(shells), 0.0);
      for (int s = 0; s < shells; ++s) {
        std::vector<char> in(nf, 0);
        for (std::size_t f = 0; f < nf; ++f)
          in[f] = shell[f] == s;
        volume[static_cast<std::size_t>(s)] = signed_volume(V, F, &in);
      }
      std::vector<int> group(static_cast<std::size_t>(shells), -1);
      std::vector<int> group_of_root(static_cast<std::size_t>(shells), -1);
      std::vector<std::vector<int>> members;
      for (const auto& [f, g] : across)
        for (Eigen::Index face : {f, g}) {
          const int s = shell[static_cast<std::size_t>(face)];
          if (group[static_cast<std::size_t>(s)] >= 0)
            continue;
          int& id = group_of_root[static_cast<std::size_t>(bodies.find(s))];
          if (id < 0) {
            id = static_cast<int>(members.size());
            members.emplace_back();
          }
          group[static_cast<std::size_t>(s)] = id;
          members[static_cast<std::size_t>(id)].push_back(s);
        }
      // A group of one shell (faces at a crossing edge that are all in one shell) has
      // nothing to unite.
      std::vector<std::vector<int>> groups;
      for (std::vector<int>& m : members) {
        if (m.size() < 2) {
          for (int s : m)
            group[static_cast<std::size_t>(s)] = -1;
          continue;
        }
        for (int s : m)
          group[static_cast<std::size_t>(s)] = static_cast<int>(groups.size());
        groups.push_back(std::move(m));
      }
      members = std::move(groups);
      if (members.empty()) {
        // Only a shell passing through itself along shared edges: no union resolves that.
        result.crossings_left = !crossing_edges.empty();
        result.why_left = "a surface passes through itself along edges it shares with itself";
        break;
      }
      bool mixed = false;
      for (const std::vector<int>& m : members) {
        bool positive = false, negative = false;
        for (int s : m)
          (volume[static_cast<std::size_t>(s)] >= 0.0 ? positive : negative) = true;
        mixed = mixed || (positive && negative);
      }
      UnitedShells united;
      if (!mixed)
        united = unite_shells(V, F, shell, group, members);
      if (mixed || !united.ok) {
        // The winding numbers of the crossing shells together may still tell the solid.
        if (!winding_tried_all) {
          winding_tried_all = true;
          if (resolve_by_winding(result, current, false, notes)) {
            current = find_self_intersections(result.vertices, result.faces);
            continue;
          }
        }
        result.crossings_left = !crossing_edges.empty();
        result.why_left =
            mixed ? "shells of opposite orientation cross (a cavity wall crossing an outer "
                    "skin?): which of them bounds a cavity cannot be told"
                  : "the union of the overlapping bodies failed (" + united.failure + ")";
        break;
      }
      for (const std::vector<int>& m : members) {
        std::vector<char> in(nf, 0);
        std::size_t removed = 0;
        double sum = 0.0;
        for (std::size_t f = 0; f < nf; ++f)
          if (std::find(m.begin(), m.end(), shell[f]) != m.end()) {
            in[f] = 1;
            ++removed;
          }
        for (int s : m)
          sum += std::abs(volume[static_cast<std::size_t>(s)]);
        // Where the union changes the surfaces: along the curves where they cross. The
        // segment where faces f and g cross lies in the intersection of their bounding
        // boxes, so the union of those boxes bounds the curves tightly even where the faces
        // are large (CAD facets).
        const auto face_box = [&](Eigen::Index face) {
          Eigen::AlignedBox3d b;
          for (int k = 0; k < 3; ++k)
            b.extend(Eigen::Vector3d(V.row(F(face, k))));
          return b;
        };
        Eigen::AlignedBox3d box;
        for (const auto& [f, g] : across)
          if (in[static_cast<std::size_t>(f)] || in[static_cast<std::size_t>(g)])
            box.extend(face_box(f).intersection(face_box(g)));
        const Eigen::AlignedBox3d bodies_box = box_of(V, F, in);
        if (box.isEmpty())
          box = bodies_box;
        SurfaceRepairStep step;
        step.where = box.center();
        step.size = box.diagonal().norm();
        step.faces_removed = removed;
        step.description = "united " + counted(m.size(), "overlapping body", "overlapping bodies") +
                           " where their surfaces cross, around " + point(step.where) + ", " +
                           number(step.size) + " across (the bodies " +
                           number(bodies_box.diagonal().norm()) + " across, volumes adding up to " +
                           number(sum) + "), into the boundary of their union";
        result.unions.push_back(std::move(step));
      }
      result.vertices = std::move(united.vertices);
      result.faces = std::move(united.faces);
    }
    current = find_self_intersections(result.vertices, result.faces);
  }
  result.left = std::move(current);
  if (result.left.pairs > 0 || result.crossings_left)
    result.unresolved =
        unresolved_zones(result.vertices, result.faces, result.left, notes, result.why_left,
                         result.crossings_left, crossing_edges);
  return result;
}

}  // namespace bemshape::geometry
