#pragma once
// Disjoint sets over the integers 0..n−1 with path halving: the connected pieces of a mesh
// (shells, vertex fans around a non-manifold vertex, edge-connected face sets).

#include <cstddef>
#include <numeric>
#include <vector>

namespace bemshape::geometry {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  /// The representative of x's set.
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  /// Joins the sets of a and b.
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

}  // namespace bemshape::geometry
