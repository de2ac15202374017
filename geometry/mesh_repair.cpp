#include "geometry/mesh_repair.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "geometry/mesh_validation.hpp"

namespace bemshape::geometry {
namespace {

using Triangle = std::array<int, 3>;

bool is_collapsed(const Triangle& t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

// Each pass splits at most one neighbour per zero-area face; a chain of k zero-area faces
// sharing longest edges needs k passes. Beyond this the remaining ones are reported.
constexpr int kMaxZeroAreaPasses = 32;

}  // namespace

FaceCleanup remove_degenerate_faces(const Eigen::MatrixX3d& vertices,
                                    const Eigen::MatrixX3i& faces) {
  FaceCleanup result;
  std::vector<Triangle> tris;
  tris.reserve(static_cast<std::size_t>(faces.rows()));
  std::set<Triangle> seen;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Triangle t{faces(f, 0), faces(f, 1), faces(f, 2)};
    if (is_collapsed(t)) {
      ++result.collapsed_removed;
      continue;
    }
    Triangle key = t;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) {
      ++result.duplicates_removed;
      continue;
    }
    tris.push_back(t);
  }

  Eigen::MatrixX3i one(1, 3);  // the face relative_height is asked about, reused
  auto zero_area = [&](const Triangle& t) {
    one << t[0], t[1], t[2];
    return relative_height(vertices, one, 0) <= kZeroAreaRelativeHeight;
  };

  for (int pass = 0; pass < kMaxZeroAreaPasses; ++pass) {
    // Faces using each undirected edge, gathered at the pass's first zero-area face (most
    // parts have none).
    std::map<std::pair<int, int>, std::vector<std::size_t>> edge_faces;
    const auto gather_edge_faces = [&] {
      for (std::size_t f = 0; f < tris.size(); ++f)
        for (int k = 0; k < 3; ++k) {
          const int a = tris[f][static_cast<std::size_t>(k)],
                    b = tris[f][static_cast<std::size_t>((k + 1) % 3)];
          edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
        }
    };
    std::vector<char> removed(tris.size(), 0), touched(tris.size(), 0);
    std::vector<Triangle> added;
    std::size_t left = 0;
    for (std::size_t f = 0; f < tris.size(); ++f) {
      if (!zero_area(tris[f]))
        continue;
      if (edge_faces.empty())
        gather_edge_faces();
      if (touched[f]) {
        ++left;
        continue;
      }
      // The middle corner m is the one opposite the longest edge (p, q).
      const Triangle& t = tris[f];
      int longest = 0;
      double best = -1.0;
      for (int k = 0; k < 3; ++k) {
        const double len = (vertices.row(t[static_cast<std::size_t>(k)]) -
                            vertices.row(t[static_cast<std::size_t>((k + 1) % 3)]))
                               .squaredNorm();
        if (len > best) {
          best = len;
          longest = k;
        }
      }
      const int p = t[static_cast<std::size_t>(longest)],
                q = t[static_cast<std::size_t>((longest + 1) % 3)];
      const int m = t[static_cast<std::size_t>((longest + 2) % 3)];
      const std::vector<std::size_t>& users = edge_faces[{std::min(p, q), std::max(p, q)}];
      if (users.size() != 2) {
        ++left;
        continue;
      }
      const std::size_t g = users[0] == f ? users[1] : users[0];
      if (touched[g] || removed[g]) {
        ++left;
        continue;
      }
      const Triangle& n = tris[g];
      int k = 0;
      while (!((n[static_cast<std::size_t>(k)] == p || n[static_cast<std::size_t>(k)] == q) &&
               (n[static_cast<std::size_t>((k + 1) % 3)] == p ||
                n[static_cast<std::size_t>((k + 1) % 3)] == q)))
        ++k;
      const int x = n[static_cast<std::size_t>(k)], y = n[static_cast<std::size_t>((k + 1) % 3)],
                r = n[static_cast<std::size_t>((k + 2) % 3)];
      if (r == m) {
        ++left;
        continue;
      }
      added.push_back({x, m, r});
      added.push_back({m, y, r});
      removed[f] = removed[g] = 1;
      touched[f] = touched[g] = 1;
      ++result.zero_area_removed;
    }
    std::vector<Triangle> next;
    next.reserve(tris.size() + added.size());
    for (std::size_t f = 0; f < tris.size(); ++f)
      if (!removed[f])
        next.push_back(tris[f]);
    next.insert(next.end(), added.begin(), added.end());
    tris = std::move(next);
    result.zero_area_left = left;
    if (added.empty())
      break;
  }
  result.zero_area_left = 0;
  for (const Triangle& t : tris)
    if (zero_area(t))
      ++result.zero_area_left;

  // Compact: keep only vertices that some face uses, in their original order.
  std::vector<int> new_index(static_cast<std::size_t>(vertices.rows()), -1);
  for (const Triangle& t : tris)
    for (int v : t)
      new_index[static_cast<std::size_t>(v)] = 0;
  int count = 0;
  for (int& idx : new_index)
    if (idx == 0)
      idx = count++;
  result.unreferenced_removed = static_cast<std::size_t>(vertices.rows() - count);
  result.vertices.resize(count, 3);
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    if (new_index[static_cast<std::size_t>(v)] >= 0)
      result.vertices.row(new_index[static_cast<std::size_t>(v)]) = vertices.row(v);
  result.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int k = 0; k < 3; ++k)
      result.faces(static_cast<Eigen::Index>(f), k) =
          new_index[static_cast<std::size_t>(tris[f][static_cast<std::size_t>(k)])];
  return result;
}

}  // namespace bemshape::geometry
