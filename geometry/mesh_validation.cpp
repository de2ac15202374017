#include "geometry/mesh_validation.hpp"
#include "geometry/union_find.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <numeric>
#include <set>

namespace bemshape::geometry {
namespace {

bool collapsed(const Eigen::MatrixX3i& faces, Eigen::Index f) {
  return faces(f, 0) == faces(f, 1) || faces(f, 1) == faces(f, 2) || faces(f, 0) == faces(f, 2);
}

/// One use of an undirected edge {lo, hi} by face `face`, traversed lo→hi if `forward`.
struct EdgeUse {
  int lo, hi, face, corner;
  bool forward;
};

/// All edge uses of non-collapsed faces, sorted by (lo, hi, face) so that uses of one edge
/// are adjacent: bucketed by lo in face order (a counting sort, linear in the uses), then
/// each vertex's few uses ordered by hi, stably, so that equal edges stay in face order.
std::vector<EdgeUse> sorted_edge_uses(const Eigen::MatrixX3i& faces) {
  int vertices = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    vertices = std::max(vertices, faces.row(f).maxCoeff() + 1);
  std::vector<int> start(static_cast<std::size_t>(vertices) + 1, 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (collapsed(faces, f))
      continue;
    for (int k = 0; k < 3; ++k)
      ++start[static_cast<std::size_t>(std::min(faces(f, k), faces(f, (k + 1) % 3))) + 1];
  }
  for (std::size_t v = 1; v < start.size(); ++v)
    start[v] += start[v - 1];
  std::vector<EdgeUse> uses(static_cast<std::size_t>(start.back()));
  std::vector<int> next(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (collapsed(faces, f))
      continue;
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      const int lo = std::min(a, b);
      uses[static_cast<std::size_t>(next[static_cast<std::size_t>(lo)]++)] = {
          lo, std::max(a, b), static_cast<int>(f), k, a < b};
    }
  }
  for (int v = 0; v < vertices; ++v) {  // insertion sort: stable, and a vertex has few uses
    const int begin = start[static_cast<std::size_t>(v)], end = start[static_cast<std::size_t>(v) + 1];
    for (int i = begin + 1; i < end; ++i) {
      const EdgeUse use = uses[static_cast<std::size_t>(i)];
      int j = i;
      for (; j > begin && uses[static_cast<std::size_t>(j - 1)].hi > use.hi; --j)
        uses[static_cast<std::size_t>(j)] = uses[static_cast<std::size_t>(j - 1)];
      uses[static_cast<std::size_t>(j)] = use;
    }
  }
  return uses;
}

/// Calls visit(first, last) for each run of uses of the same edge.
template <typename Visit>
void for_each_edge(const std::vector<EdgeUse>& uses, Visit&& visit) {
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
      ++j;
    visit(i, j);
    i = j;
  }
}

}  // namespace

double relative_height(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                       Eigen::Index f) {
  const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)),
                        c = vertices.row(faces(f, 2));
  const double longest2 =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (longest2 == 0.0)
    return 0.0;
  return (b - a).cross(c - a).norm() / longest2;
}

std::vector<int> shell_labels(const Eigen::MatrixX3i& faces, std::size_t* count) {
  const std::vector<EdgeUse> uses = sorted_edge_uses(faces);
  UnionFind components(static_cast<std::size_t>(faces.rows()));
  for_each_edge(uses, [&](std::size_t i, std::size_t j) {
    for (std::size_t k = i + 1; k < j; ++k)
      components.unite(uses[i].face, uses[k].face);
  });
  std::vector<int> label(static_cast<std::size_t>(faces.rows()), -1);
  std::vector<int> root_label(static_cast<std::size_t>(faces.rows()), -1);
  int next = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (collapsed(faces, f))
      continue;
    int& l = root_label[static_cast<std::size_t>(components.find(static_cast<int>(f)))];
    if (l < 0)
      l = next++;
    label[static_cast<std::size_t>(f)] = l;
  }
  if (count)
    *count = static_cast<std::size_t>(next);
  return label;
}

MeshValidation validate_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  MeshValidation result;
  auto point = [&](int v) -> Eigen::Vector3d { return vertices.row(v).transpose(); };
  auto centroid = [&](Eigen::Index f) -> Eigen::Vector3d {
    return (point(faces(f, 0)) + point(faces(f, 1)) + point(faces(f, 2))) / 3.0;
  };

  // Per-face rules.
  std::set<std::array<int, 3>> seen;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (collapsed(faces, f)) {
      result.collapsed_faces.add(centroid(f));
      continue;
    }
    const double h = relative_height(vertices, faces, f);
    if (h <= kZeroAreaRelativeHeight)
      result.zero_area_faces.add(centroid(f));
    else if (h < kNeedleRelativeHeight)
      result.needle_faces.add(centroid(f));
    std::array<int, 3> key{faces(f, 0), faces(f, 1), faces(f, 2)};
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second)
      result.duplicate_faces.add(centroid(f));
  }

  // Edge rules, and the fans around each vertex: corners (face, k) at the same vertex are
  // joined when their faces share a manifold edge at that vertex.
  const std::vector<EdgeUse> uses = sorted_edge_uses(faces);
  UnionFind fans(static_cast<std::size_t>(3 * faces.rows()));
  auto corner_of = [&](int face, int vertex) {
    int k = 0;
    while (faces(face, k) != vertex)
      ++k;
    return 3 * face + k;
  };
  for_each_edge(uses, [&](std::size_t i, std::size_t j) {
    const Eigen::Vector3d midpoint = 0.5 * (point(uses[i].lo) + point(uses[i].hi));
    const std::size_t n = j - i;
    if (n == 1) {
      result.boundary_edges.add(midpoint);
    } else if (n > 2) {
      result.nonmanifold_edges.add(midpoint);
    } else {
      if (uses[i].forward == uses[i + 1].forward)
        result.inconsistent_edges.add(midpoint);
      for (int v : {uses[i].lo, uses[i].hi})
        fans.unite(corner_of(uses[i].face, v), corner_of(uses[i + 1].face, v));
    }
  });
  std::vector<int> first_fan(static_cast<std::size_t>(vertices.rows()), -1);
  std::vector<char> flagged(static_cast<std::size_t>(vertices.rows()), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (collapsed(faces, f))
      continue;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(faces(f, k));
      const int fan = fans.find(static_cast<int>(3 * f + k));
      if (first_fan[v] < 0)
        first_fan[v] = fan;
      else if (first_fan[v] != fan && !flagged[v]) {
        flagged[v] = 1;
        result.nonmanifold_vertices.add(point(faces(f, k)));
      }
    }
  }
  shell_labels(faces, &result.shells);
  return result;
}

}  // namespace bemshape::geometry
