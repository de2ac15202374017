#include "geometry/face_adjacency.hpp"

#include <algorithm>
#include <array>

namespace bemshape::geometry {

std::vector<std::vector<int>> edge_neighbours(const Eigen::MatrixX3i& faces) {
  const auto nf = static_cast<std::size_t>(faces.rows());
  // Every face's three edges as (lower vertex, higher vertex, face), sorted: the faces of
  // one edge are a run.
  std::vector<std::array<int, 3>> edges;
  edges.reserve(3 * nf);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f)});
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::vector<int>> neighbours(nf);
  for (std::size_t first = 0; first < edges.size();) {
    std::size_t end = first + 1;
    while (end < edges.size() && edges[end][0] == edges[first][0] &&
           edges[end][1] == edges[first][1])
      ++end;
    for (std::size_t i = first; i < end; ++i)
      for (std::size_t j = first; j < end; ++j) {
        const int f = edges[i][2], g = edges[j][2];
        if (f != g) neighbours[static_cast<std::size_t>(f)].push_back(g);
      }
    first = end;
  }
  // Two faces sharing two edges (a fold) would be listed twice.
  for (std::vector<int>& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

}  // namespace bemshape::geometry
