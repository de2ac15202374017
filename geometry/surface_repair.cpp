#include "geometry/surface_repair.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <numeric>

#include "core/errors.hpp"
#include "geometry/constructive_solids.hpp"
#include "geometry/detail/cgal_mesh_repair.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/union_find.hpp"

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

/// The faces of one shell with their own compact vertex array.
SurfaceMesh shell_mesh(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f,
                       const std::vector<int>& shell, int which) {
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  std::vector<Eigen::Index> rows;
  int next = 0;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (shell[static_cast<std::size_t>(i)] == which) {
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
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    if (group[static_cast<std::size_t>(shell[static_cast<std::size_t>(i)])] >= 0)
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
  for (const SurfaceMesh& mesh : united) {
    const int offset = static_cast<int>(points.size());
    for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i)
      points.push_back(mesh.vertices().row(i).transpose());
    for (Eigen::Index i = 0; i < mesh.num_faces(); ++i)
      triangles.push_back({mesh.faces()(i, 0) + offset, mesh.faces()(i, 1) + offset,
                           mesh.faces()(i, 2) + offset});
  }
  result.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    result.vertices.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  result.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      result.faces(static_cast<Eigen::Index>(i), k) = triangles[i][static_cast<std::size_t>(k)];
  return result;
}

std::string describe_fill(const detail::CgalHole& hole) {
  return "filled a hole of " + counted(hole.edges, "edge", "edges") + ", " +
         number(hole.extent) + " across, at " + point(hole.centre) + " with " +
         counted(hole.faces_added, "triangle", "triangles") + " (area " +
         number(hole.area_added) + "; rim flat to " + number(hole.out_of_plane) +
         (hole.faired ? "" : "; fairing failed, minimal-area patch kept") + ")";
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

IntersectionRepair resolve_self_intersections(
    const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
    const SelfIntersections& found, double repair_length,
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& crossing_edges) {
  IntersectionRepair result;
  result.vertices = vertices;
  result.faces = faces;
  SelfIntersections current = found;
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
    if (ring == 0 && union_rounds == 0) {
      result.pairs_within_shells = local.size();
      result.pairs_between_shells = across.size();
    }

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
      if (mixed) {
        result.crossings_left = !crossing_edges.empty();
        result.why_left = "shells of opposite orientation cross (a cavity wall crossing an "
                          "outer skin?): which of them bounds a cavity cannot be told";
        break;
      }
      UnitedShells united = unite_shells(V, F, shell, group, members);
      if (!united.ok) {
        result.crossings_left = !crossing_edges.empty();
        result.why_left = "the union of the overlapping bodies failed (" + united.failure + ")";
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
  return result;
}

}  // namespace bemshape::geometry
