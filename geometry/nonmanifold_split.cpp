#include "geometry/nonmanifold_split.hpp"
#include "geometry/union_find.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

namespace bemshape::geometry {
namespace {

/// Face `face` uses the undirected edge {lo, hi} as its edge `corner` → corner + 1,
/// traversing it lo → hi if `forward`.
struct EdgeUse {
  int lo, hi, face, corner;
  bool forward;
};

/// Position of vertex v among the corners of face f (0, 1, 2).
int corner_of(const Eigen::MatrixX3i& faces, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (faces(f, k) == v)
      return k;
  return -1;
}

}  // namespace

NonmanifoldSplit split_nonmanifold(const Eigen::MatrixX3d& vertices,
                                   const Eigen::MatrixX3i& faces) {
  NonmanifoldSplit result;
  const auto nf = static_cast<std::size_t>(faces.rows());
  auto point = [&](int v) -> Eigen::Vector3d { return vertices.row(v).transpose(); };

  std::vector<EdgeUse> uses;
  uses.reserve(3 * nf);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      uses.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f), k, a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.lo, x.hi, x.face, x.corner) < std::tie(y.lo, y.hi, y.face, y.corner);
  });
  // Runs [start[e], start[e + 1]) of uses of one edge.
  std::vector<std::size_t> start;
  for (std::size_t i = 0; i < uses.size(); ++i)
    if (i == 0 || uses[i].lo != uses[i - 1].lo || uses[i].hi != uses[i - 1].hi)
      start.push_back(i);
  start.push_back(uses.size());

  // Pieces of surface connected through manifold edges, each with its signed volume if it
  // is closed (every edge used 0 or 2 times by its own faces).
  UnionFind pieces(nf);
  for (std::size_t e = 0; e + 1 < start.size(); ++e)
    if (start[e + 1] - start[e] == 2)
      pieces.unite(uses[start[e]].face, uses[start[e] + 1].face);
  std::vector<int> piece(nf);
  for (std::size_t f = 0; f < nf; ++f)
    piece[f] = pieces.find(static_cast<int>(f));
  std::vector<double> volume(nf, 0.0);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto i = static_cast<Eigen::Index>(f);
    volume[static_cast<std::size_t>(piece[f])] +=
        point(faces(i, 0)).dot(point(faces(i, 1)).cross(point(faces(i, 2)))) / 6.0;
  }
  std::vector<char> open(nf, 0);
  for (std::size_t e = 0; e + 1 < start.size(); ++e) {
    std::vector<int> owners;
    for (std::size_t i = start[e]; i < start[e + 1]; ++i)
      owners.push_back(piece[static_cast<std::size_t>(uses[i].face)]);
    std::sort(owners.begin(), owners.end());
    for (std::size_t i = 0; i < owners.size();) {
      std::size_t j = i;
      while (j < owners.size() && owners[j] == owners[i])
        ++j;
      if ((j - i) % 2 != 0)
        open[static_cast<std::size_t>(owners[i])] = 1;
      i = j;
    }
  }
  // +1 outward, −1 inward, 0 unknown (open piece or no volume).
  auto orientation = [&](int f) -> int {
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(f)]);
    if (open[p] || volume[p] == 0.0)
      return 0;
    return volume[p] > 0.0 ? 1 : -1;
  };

  // neighbour[3f + k]: the face across edge k of face f, −1 if none.
  std::vector<int> neighbour(3 * nf, -1);
  auto link = [&](const EdgeUse& x, const EdgeUse& y) {
    neighbour[3 * static_cast<std::size_t>(x.face) + static_cast<std::size_t>(x.corner)] = y.face;
    neighbour[3 * static_cast<std::size_t>(y.face) + static_cast<std::size_t>(y.corner)] = x.face;
  };
  for (std::size_t e = 0; e + 1 < start.size(); ++e) {
    const std::size_t n = start[e + 1] - start[e];
    if (n == 2)
      link(uses[start[e]], uses[start[e] + 1]);
    if (n <= 2)
      continue;

    // Sort the faces around the edge by the angle of their third vertex about the axis.
    const EdgeUse& first = uses[start[e]];
    const Eigen::Vector3d lo = point(first.lo);
    const Eigen::Vector3d axis = (point(first.hi) - lo).normalized();
    auto radial = [&](const EdgeUse& use) {
      Eigen::Vector3d d = point(faces(use.face, (use.corner + 2) % 3)) - lo;
      return Eigen::Vector3d(d - d.dot(axis) * axis);
    };
    Eigen::Vector3d ref = radial(first);
    if (ref.norm() == 0.0)
      ref = axis.unitOrthogonal();
    ref.normalize();
    const Eigen::Vector3d ref2 = axis.cross(ref);
    std::vector<std::pair<double, EdgeUse>> around;
    for (std::size_t i = start[e]; i < start[e + 1]; ++i) {
      const Eigen::Vector3d d = radial(uses[i]);
      around.push_back({std::atan2(d.dot(ref2), d.dot(ref)), uses[i]});
    }
    std::stable_sort(around.begin(), around.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });

    // A face traversing lo → hi has its normal along axis × radial, the counter-clockwise
    // tangent: outward-oriented, its material lies clockwise of it.
    auto material_ccw = [&](const EdgeUse& u) {
      const int s = orientation(u.face);
      return (s > 0 && !u.forward) || (s < 0 && u.forward);
    };
    auto material_cw = [&](const EdgeUse& u) {
      const int s = orientation(u.face);
      return (s > 0 && u.forward) || (s < 0 && !u.forward);
    };
    auto score = [&](const EdgeUse& a, const EdgeUse& b) {
      return 4 * (piece[static_cast<std::size_t>(a.face)] ==
                  piece[static_cast<std::size_t>(b.face)]) +
             2 * (a.forward != b.forward) + (material_ccw(a) && material_cw(b));
    };
    // The pairing of angular neighbours of a ring of faces (in angular order) that scores
    // best: for an even count the two perfect matchings of the cycle; for an odd count, leave
    // face m out and pair the path m+1 … m+count−1. Returns the face left out, if any.
    auto match = [&](const std::vector<EdgeUse>& ring) -> const EdgeUse* {
      const std::size_t count = ring.size();
      int best = -1;
      std::vector<std::pair<std::size_t, std::size_t>> best_pairs;
      std::size_t left_out = count;
      auto consider = [&](std::size_t from, std::size_t length, std::size_t out) {
        std::vector<std::pair<std::size_t, std::size_t>> pairs;
        int total = 0;
        for (std::size_t k = 0; k + 1 < length; k += 2) {
          const std::size_t x = (from + k) % count, y = (from + k + 1) % count;
          pairs.push_back({x, y});
          total += score(ring[x], ring[y]);
        }
        if (total > best) {
          best = total;
          best_pairs = std::move(pairs);
          left_out = out;
        }
      };
      if (count % 2 == 0) {
        consider(0, count, count);
        consider(1, count, count);
      } else {
        for (std::size_t m = 0; m < count; ++m)
          consider(m + 1, count - 1, m);
      }
      for (const auto& [x, y] : best_pairs)
        link(ring[x], ring[y]);
      return left_out < count ? &ring[left_out] : nullptr;
    };

    // Faces of one piece are paired among themselves, so every body stays whole; the faces
    // left over (one per piece with an odd number here, e.g. a fin) are paired among
    // themselves, and one may stay alone.
    std::vector<int> piece_ids;
    for (const auto& entry : around) {
      const int id = piece[static_cast<std::size_t>(entry.second.face)];
      if (std::find(piece_ids.begin(), piece_ids.end(), id) == piece_ids.end())
        piece_ids.push_back(id);
    }
    std::vector<EdgeUse> leftovers;
    std::vector<std::vector<std::size_t>> positions(piece_ids.size());
    for (std::size_t p = 0; p < piece_ids.size(); ++p) {
      std::vector<EdgeUse> ring;
      for (std::size_t i = 0; i < n; ++i)
        if (piece[static_cast<std::size_t>(around[i].second.face)] == piece_ids[p]) {
          ring.push_back(around[i].second);
          positions[p].push_back(i);
        }
      if (ring.size() == 1) {
        leftovers.push_back(ring[0]);
      } else if (const EdgeUse* alone = match(ring)) {
        leftovers.push_back(*alone);
      }
    }
    if (leftovers.size() >= 2) {
      std::stable_sort(leftovers.begin(), leftovers.end(), [&](const EdgeUse& x, const EdgeUse& y) {
        auto at = [&](const EdgeUse& u) {
          for (std::size_t i = 0; i < n; ++i)
            if (around[i].second.face == u.face && around[i].second.corner == u.corner)
              return i;
          return n;
        };
        return at(x) < at(y);
      });
      if (match(leftovers) != nullptr)
        ++result.faces_unpaired;
    } else if (leftovers.size() == 1) {
      ++result.faces_unpaired;
    }

    // Bodies pass through each other here if, going around the edge, some wedge lies inside
    // two of them: the winding number changes by −1 across a face traversing lo → hi (its
    // normal points counter-clockwise, out of the material) and by +1 across the others, and
    // a span of 2 or more means overlap. Pieces that each have two faces side by side only
    // touch, whatever their orientation says (an inverted body is repaired later).
    bool side_by_side = true;
    for (std::size_t p = 0; p < piece_ids.size(); ++p) {
      const std::vector<std::size_t>& at = positions[p];
      side_by_side = side_by_side && at.size() == 2 &&
                     (at[1] == at[0] + 1 || (at[0] == 0 && at[1] == n - 1));
    }
    bool crossing = false;
    if (!side_by_side) {
      int winding = 0, lowest = 0, highest = 0;
      for (std::size_t i = 0; i < n; ++i) {
        winding += around[i].second.forward ? -1 : 1;
        lowest = std::min(lowest, winding);
        highest = std::max(highest, winding);
      }
      crossing = winding == 0 && highest - lowest >= 2;
    }
    if (crossing) {
      if (result.edges_crossing++ == 0)
        result.first_crossing = 0.5 * (lo + point(first.hi));
      result.crossing_edges.emplace_back(lo, point(first.hi));
    }
    if (result.edges_split++ == 0)
      result.first_edge = 0.5 * (lo + point(first.hi));
  }

  // Fans: corners (f, k) at the same vertex joined across every linked edge at that vertex.
  UnionFind fans(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = neighbour[3 * f + static_cast<std::size_t>(k)];
      if (g < 0)
        continue;
      for (int end : {k, (k + 1) % 3}) {
        const int v = faces(static_cast<Eigen::Index>(f), end);
        const int c = corner_of(faces, g, v);
        if (c >= 0)
          fans.unite(static_cast<int>(3 * f) + end, 3 * g + c);
      }
    }
  // For each vertex, its fans in order of first appearance; fans after the first get copies.
  std::vector<std::vector<int>> corners_of(static_cast<std::size_t>(vertices.rows()));
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      corners_of[static_cast<std::size_t>(faces(static_cast<Eigen::Index>(f), k))].push_back(
          static_cast<int>(3 * f) + k);
  result.faces = faces;
  std::vector<Eigen::Vector3d> copies;
  const auto nv = static_cast<int>(vertices.rows());
  for (int v = 0; v < nv; ++v) {
    const std::vector<int>& corners = corners_of[static_cast<std::size_t>(v)];
    std::vector<int> roots, fan_of(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const int root = fans.find(corners[i]);
      const auto it = std::find(roots.begin(), roots.end(), root);
      fan_of[i] = static_cast<int>(it - roots.begin());
      if (it == roots.end())
        roots.push_back(root);
    }
    if (roots.size() <= 1)
      continue;
    if (result.vertices_split++ == 0)
      result.first_vertex = point(v);
    result.copies_added += roots.size() - 1;
    // Fan i ≥ 1 gets the copy nv + (copies so far) + i − 1.
    const int base = nv + static_cast<int>(copies.size()) - 1;
    for (std::size_t i = 0; i < corners.size(); ++i)
      if (fan_of[i] > 0)
        result.faces(corners[i] / 3, corners[i] % 3) = base + fan_of[i];
    for (std::size_t k = 1; k < roots.size(); ++k)
      copies.push_back(point(v));
  }
  result.vertices.resize(vertices.rows() + static_cast<Eigen::Index>(copies.size()), 3);
  result.vertices.topRows(vertices.rows()) = vertices;
  for (std::size_t k = 0; k < copies.size(); ++k)
    result.vertices.row(vertices.rows() + static_cast<Eigen::Index>(k)) = copies[k].transpose();
  return result;
}

}  // namespace bemshape::geometry
