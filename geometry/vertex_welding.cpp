#include "geometry/vertex_welding.hpp"

#include <array>
#include <cmath>
#include <map>
#include <unordered_map>
#include <vector>

namespace bemshape::geometry {
namespace {

struct CellHash {
  std::size_t operator()(const std::array<long long, 3>& c) const noexcept {
    std::size_t h = 1469598103934665603ull;
    for (long long x : c)
      h = (h ^ static_cast<std::size_t>(x)) * 1099511628211ull;
    return h;
  }
};

}  // namespace

WeldResult weld_vertices(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                         double relative_tolerance) {
  WeldResult result;
  const Eigen::Index nv = vertices.rows();

  // Stage 1: exact duplicates. Adding 0.0 turns −0.0 into +0.0 so both compare equal.
  std::vector<int> exact_of(static_cast<std::size_t>(nv));
  std::vector<int> exact_rep;  // input index of each exactly distinct position
  {
    std::map<std::array<double, 3>, int> seen;
    for (Eigen::Index v = 0; v < nv; ++v) {
      const std::array<double, 3> key{vertices(v, 0) + 0.0, vertices(v, 1) + 0.0,
                                      vertices(v, 2) + 0.0};
      auto [it, inserted] = seen.emplace(key, static_cast<int>(exact_rep.size()));
      if (inserted)
        exact_rep.push_back(static_cast<int>(v));
      exact_of[static_cast<std::size_t>(v)] = it->second;
    }
  }
  result.merged_exact = static_cast<std::size_t>(nv) - exact_rep.size();

  // Stage 2: within tolerance, by hashing into cubic cells of the tolerance's size and
  // searching the 27 neighbouring cells.
  double diagonal = 0.0;
  if (nv > 0)
    diagonal = (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
  result.tolerance = relative_tolerance * diagonal;
  const double tol = result.tolerance;
  std::vector<int> tol_of(exact_rep.size());
  std::vector<int> kept;  // input index of each kept vertex
  if (tol > 0.0) {
    std::unordered_map<std::array<long long, 3>, std::vector<int>, CellHash> grid;
    const Eigen::RowVector3d origin = vertices.colwise().minCoeff();
    for (std::size_t e = 0; e < exact_rep.size(); ++e) {
      const Eigen::RowVector3d p = vertices.row(exact_rep[e]);
      std::array<long long, 3> cell;
      for (int k = 0; k < 3; ++k)
        cell[static_cast<std::size_t>(k)] =
            static_cast<long long>(std::floor((p(k) - origin(k)) / tol));
      int found = -1;
      double best = tol;
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
            if (it == grid.end())
              continue;
            for (int k : it->second) {
              const double d = (vertices.row(kept[static_cast<std::size_t>(k)]) - p).norm();
              if (d <= best && (found < 0 || d < best || k < found)) {
                best = d;
                found = k;
              }
            }
          }
      if (found < 0) {
        found = static_cast<int>(kept.size());
        kept.push_back(exact_rep[e]);
        grid[cell].push_back(found);
      }
      tol_of[e] = found;
    }
  } else {
    kept = exact_rep;
    for (std::size_t e = 0; e < exact_rep.size(); ++e)
      tol_of[e] = static_cast<int>(e);
  }
  result.merged_within_tolerance = exact_rep.size() - kept.size();

  // Re-index faces and drop vertices no face uses.
  std::vector<int> new_index(kept.size(), -1);
  int count = 0;
  result.faces.resize(faces.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int w =
          tol_of[static_cast<std::size_t>(exact_of[static_cast<std::size_t>(faces(f, k))])];
      int& idx = new_index[static_cast<std::size_t>(w)];
      if (idx < 0)
        idx = count++;
      result.faces(f, k) = idx;
    }
  result.unreferenced_removed = kept.size() - static_cast<std::size_t>(count);
  result.vertices.resize(count, 3);
  for (std::size_t w = 0; w < kept.size(); ++w)
    if (new_index[w] >= 0)
      result.vertices.row(new_index[w]) = vertices.row(kept[w]);
  return result;
}

}  // namespace bemshape::geometry
