#include "geometry/winding_number_boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "core/cancellation.hpp"
#include "geometry/detail/cgal_autorefinement.hpp"
#include "geometry/winding_number.hpp"

namespace bemshape::geometry {
namespace {

/// A generalized winding number farther than this from an integer is not trusted: the
/// point is too close to another sheet (the sum itself is exact up to rounding, ~1e-12).
constexpr double kIntegerTolerance = 1e-3;
/// The point where a connected set of pieces gets its winding number lies this fraction of
/// its face's smallest altitude in front of the face's centroid: deep inside the wedge in
/// front of the face, and far from every other sheet unless one passes that close.
constexpr double kProbeOffset = 1e-3;
/// Faces of each connected set of pieces that are tried for the probe (largest first); two
/// that give an integer must agree.
constexpr std::size_t kProbeCandidates = 3;

/// Disjoint sets with an integer offset to the representative:
/// value(x) = value(find(x)) + offset_to_root(x).
class OffsetUnionFind {
 public:
  explicit OffsetUnionFind(std::size_t n) : parent_(n), offset_(n, 0) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  /// The representative of x and value(x) − value(representative).
  std::pair<std::size_t, std::int64_t> find(std::size_t x) {
    std::size_t root = x;
    std::int64_t total = 0;
    while (parent_[root] != root) {
      total += offset_[root];
      root = parent_[root];
    }
    // Path compression: every node on the path points at the root with its full offset.
    std::int64_t remaining = total;
    while (parent_[x] != x) {
      const std::size_t next = parent_[x];
      const std::int64_t own = offset_[x];
      parent_[x] = root;
      offset_[x] = remaining;
      remaining -= own;
      x = next;
    }
    return {root, total};
  }
  /// Records value(y) − value(x) = d; false if it contradicts what is known.
  bool relate(std::size_t x, std::size_t y, std::int64_t d) {
    const auto [rx, ox] = find(x);
    const auto [ry, oy] = find(y);
    if (rx == ry)
      return oy - ox == d;
    parent_[ry] = rx;
    offset_[ry] = ox + d - oy;
    return true;
  }

 private:
  std::vector<std::size_t> parent_;
  std::vector<std::int64_t> offset_;
};

/// A piece: one triangle of the refined surface, coinciding copies merged.
struct Piece {
  std::array<int, 3> corner{};  ///< welded vertex indices, oriented
  std::int64_t step = 0;        ///< w_back − w_front (coinciding copies add up)
};

/// One piece at an edge (a, b) with a < b: whether the piece runs a → b, and its third corner.
struct Incidence {
  std::size_t piece = 0;
  bool forward = false;
  int third = 0;
};

/// Node of the labelling: side 0 (front) or 1 (back) of piece p.
std::size_t node(std::size_t piece, int side) {
  return 2 * piece + static_cast<std::size_t>(side);
}

Eigen::Vector3d row(const Eigen::MatrixX3d& v, int i) {
  return v.row(i).transpose();
}

/// The angular order of the pieces about the edge p → q (counter-clockwise about q − p),
/// with exact predicates; false if two pieces leave the edge in the same half-plane (sheets
/// lying on each other) or a piece is degenerate.
bool sort_about_edge(const Eigen::MatrixX3d& v, int a, int b, std::vector<Incidence>& around) {
  const Eigen::Vector3d p = row(v, a), q = row(v, b);
  const Eigen::Vector3d reference = row(v, around.front().third);
  bool degenerate = false;
  // 0: the reference ray; 1: (0, π); 2: the opposite ray; 3: (π, 2π).
  const auto half = [&](const Incidence& i) {
    const Eigen::Vector3d x = row(v, i.third);
    const int o = detail::exact_orientation(p, q, reference, x);
    if (o > 0)
      return 1;
    if (o < 0)
      return 3;
    const int side = detail::exact_coplanar_orientation(p, q, reference, x);
    if (side == 0)
      degenerate = true;
    return side > 0 ? 0 : 2;
  };
  std::vector<std::pair<int, Incidence>> keyed;
  keyed.reserve(around.size());
  for (const Incidence& i : around)
    keyed.emplace_back(half(i), i);
  bool tie = false;
  const auto before = [&](const std::pair<int, Incidence>& x, const std::pair<int, Incidence>& y) {
    if (x.first != y.first)
      return x.first < y.first;
    if (x.first == 0 || x.first == 2)
      return false;  // the same ray
    return detail::exact_orientation(p, q, row(v, x.second.third), row(v, y.second.third)) > 0;
  };
  std::sort(keyed.begin(), keyed.end(), before);
  for (std::size_t i = 0; i + 1 < keyed.size(); ++i)
    if (!before(keyed[i], keyed[i + 1]))
      tie = true;
  for (std::size_t i = 0; i < keyed.size(); ++i)
    around[i] = keyed[i].second;
  return !tie && !degenerate;
}

/// Six times the signed volume of the tetrahedron (origin, a, b, c).
double six_volume(const Eigen::MatrixX3d& v, const std::array<int, 3>& c) {
  return row(v, c[0]).dot(row(v, c[1]).cross(row(v, c[2])));
}

/// The faces as their own refinement: each its own piece.
detail::CgalAutorefinement unrefined(const Eigen::MatrixX3d& vertices,
                                     const Eigen::MatrixX3i& faces) {
  detail::CgalAutorefinement same;
  same.vertices = vertices;
  same.faces = faces;
  same.source.resize(static_cast<std::size_t>(faces.rows()));
  std::iota(same.source.begin(), same.source.end(), Eigen::Index{0});
  same.ok = true;
  return same;
}

WindingNumberBoundary label(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                            bool refine) {
  WindingNumberBoundary result;
  const detail::CgalAutorefinement refined =
      refine ? detail::cgal_autorefine(vertices, faces) : unrefined(vertices, faces);
  if (!refined.ok) {
    result.failure = refined.failure;
    return result;
  }
  throw_if_cancelled();

  // Weld the copies of the curves' vertices (equal coordinates) into one vertex each.
  const auto nv = static_cast<std::size_t>(refined.vertices.rows());
  std::vector<int> order(nv);
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](int i) {
    return std::array<double, 3>{refined.vertices(i, 0), refined.vertices(i, 1),
                                 refined.vertices(i, 2)};
  };
  std::sort(order.begin(), order.end(), [&](int x, int y) { return key(x) < key(y); });
  std::vector<int> welded(nv, -1);
  Eigen::MatrixX3d v(static_cast<Eigen::Index>(nv), 3);
  int distinct = 0;
  for (std::size_t i = 0; i < nv; ++i) {
    if (i == 0 || key(order[i]) != key(order[i - 1]))
      v.row(distinct++) = refined.vertices.row(order[i]);
    welded[static_cast<std::size_t>(order[i])] = distinct - 1;
  }
  v.conservativeResize(distinct, 3);

  // Pieces: coinciding triangles merged, their steps added (+1 for each copy oriented as the
  // sorted corners, −1 for each reversed one); pieces whose copies cancel are no surface.
  std::map<std::array<int, 3>, std::int64_t> multiplicity;
  std::vector<std::size_t> pieces_of_source(static_cast<std::size_t>(faces.rows()), 0);
  for (Eigen::Index f = 0; f < refined.faces.rows(); ++f) {
    std::array<int, 3> c{welded[static_cast<std::size_t>(refined.faces(f, 0))],
                         welded[static_cast<std::size_t>(refined.faces(f, 1))],
                         welded[static_cast<std::size_t>(refined.faces(f, 2))]};
    ++pieces_of_source[static_cast<std::size_t>(refined.source[static_cast<std::size_t>(f)])];
    // A piece whose curve points were rounded onto one another is a segment: it encloses
    // nothing, and its two remaining edges, the same edge both ways, cancel.
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
      continue;
    // Rotate the smallest corner first; the orientation is then whether the other two are
    // increasing.
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    const bool even = c[1] < c[2];
    if (!even)
      std::swap(c[1], c[2]);
    multiplicity[c] += even ? 1 : -1;
  }
  for (std::size_t n : pieces_of_source)
    result.faces_split += n > 1 ? 1 : 0;
  std::vector<Piece> pieces;
  pieces.reserve(multiplicity.size());
  for (const auto& [c, m] : multiplicity) {
    if (m == 0)
      continue;
    Piece piece;
    piece.corner = m > 0 ? c : std::array<int, 3>{c[0], c[2], c[1]};
    piece.step = m > 0 ? m : -m;
    pieces.push_back(piece);
  }

  // Edges and the pieces around each.
  std::map<std::pair<int, int>, std::vector<Incidence>> edges;
  for (std::size_t p = 0; p < pieces.size(); ++p)
    for (int k = 0; k < 3; ++k) {
      const int a = pieces[p].corner[static_cast<std::size_t>(k)];
      const int b = pieces[p].corner[static_cast<std::size_t>((k + 1) % 3)];
      const int c = pieces[p].corner[static_cast<std::size_t>((k + 2) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back({p, a < b, c});
    }

  OffsetUnionFind sides(2 * pieces.size());
  for (std::size_t p = 0; p < pieces.size(); ++p)
    if (!sides.relate(node(p, 0), node(p, 1), pieces[p].step)) {
      result.failure = "inconsistent winding numbers";
      return result;
    }
  for (auto& [edge, around] : edges) {
    // The surface is closed as a chain: the steps through the edge cancel.
    std::int64_t through = 0;
    for (const Incidence& i : around)
      through += i.forward ? pieces[i.piece].step : -pieces[i.piece].step;
    if (through != 0) {
      result.failure = "the refined surface is not closed";
      return result;
    }
    if (around.size() > 2) {
      ++result.curve_edges;
      result.curves.extend(row(v, edge.first));
      result.curves.extend(row(v, edge.second));
      if (!sort_about_edge(v, edge.first, edge.second, around)) {
        result.failure = "sheets of the surface lie on each other";
        return result;
      }
    }
    // A piece running a → b faces the next piece counter-clockwise with its front (its normal
    // is (b − a) × (third − a)), one running b → a with its back; the wedge between two
    // consecutive pieces is one region.
    for (std::size_t i = 0; i < around.size(); ++i) {
      const Incidence& x = around[i];
      const Incidence& y = around[(i + 1) % around.size()];
      if (!sides.relate(node(x.piece, x.forward ? 0 : 1), node(y.piece, y.forward ? 1 : 0), 0)) {
        result.failure = "inconsistent winding numbers";
        return result;
      }
    }
  }
  throw_if_cancelled();

  // One winding number per connected set of pieces, at a point just in front of a piece.
  std::map<std::size_t, std::vector<std::size_t>> by_root;
  for (std::size_t p = 0; p < pieces.size(); ++p)
    by_root[sides.find(node(p, 0)).first].push_back(p);
  std::map<std::size_t, std::int64_t> root_value;
  for (auto& [root, members] : by_root) {
    const auto altitude = [&](std::size_t p) {
      const std::array<int, 3>& c = pieces[p].corner;
      const Eigen::Vector3d a = row(v, c[0]), b = row(v, c[1]), d = row(v, c[2]);
      const double twice_area = (b - a).cross(d - a).norm();
      const double longest = std::max({(b - a).norm(), (d - b).norm(), (a - d).norm()});
      return longest > 0.0 ? twice_area / longest : 0.0;
    };
    std::partial_sort(
        members.begin(),
        members.begin() + static_cast<std::ptrdiff_t>(std::min(kProbeCandidates, members.size())),
        members.end(), [&](std::size_t x, std::size_t y) { return altitude(x) > altitude(y); });
    bool found = false;
    std::int64_t value = 0;
    for (std::size_t i = 0; i < std::min(kProbeCandidates, members.size()); ++i) {
      const std::array<int, 3>& c = pieces[members[i]].corner;
      const Eigen::Vector3d a = row(v, c[0]), b = row(v, c[1]), d = row(v, c[2]);
      const Eigen::Vector3d normal = (b - a).cross(d - a).normalized();
      const Eigen::Vector3d probe =
          (a + b + d) / 3.0 + kProbeOffset * altitude(members[i]) * normal;
      const double w = winding_number(vertices, faces, probe);
      if (!std::isfinite(w) || std::abs(w - std::round(w)) > kIntegerTolerance)
        continue;
      const std::int64_t front = static_cast<std::int64_t>(std::llround(w));
      const std::int64_t candidate = front - sides.find(node(members[i], 0)).second;
      if (found && candidate != value) {
        result.failure = "the winding numbers of the pieces disagree";
        return result;
      }
      found = true;
      value = candidate;
    }
    if (!found) {
      result.failure = "no piece has a point of well-defined winding number in front of it";
      return result;
    }
    root_value[root] = value;
  }

  // The boundary of Ω₊ and the volumes of the levels of w.
  std::vector<std::array<int, 3>> kept;
  result.min_winding = std::numeric_limits<int>::max();
  result.max_winding = std::numeric_limits<int>::min();
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const auto [root, offset] = sides.find(node(p, 0));
    const std::int64_t front = root_value[root] + offset;
    const std::int64_t back = front + pieces[p].step;
    const double volume = six_volume(v, pieces[p].corner) / 6.0;
    result.signed_volume += static_cast<double>(pieces[p].step) * volume;
    if (front < 1 && back >= 1) {
      kept.push_back(pieces[p].corner);
      result.volume += volume;
    }
    if (front < 2 && back >= 2)
      result.overlap_volume += volume;
    if (front <= -1 && back > -1)
      result.negative_volume -= volume;
    if (front < 0 || back > 1)
      for (int c : pieces[p].corner)
        result.irregular.extend(row(v, c));
    result.min_winding = std::min(result.min_winding, static_cast<int>(front));
    result.max_winding = std::max(result.max_winding, static_cast<int>(back));
  }

  // Compact the kept pieces' vertices.
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  int used = 0;
  for (const std::array<int, 3>& c : kept)
    for (int x : c)
      if (index[static_cast<std::size_t>(x)] < 0)
        index[static_cast<std::size_t>(x)] = used++;
  result.vertices.resize(used, 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (index[static_cast<std::size_t>(i)] >= 0)
      result.vertices.row(index[static_cast<std::size_t>(i)]) = v.row(i);
  result.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t f = 0; f < kept.size(); ++f)
    for (int k = 0; k < 3; ++k)
      result.faces(static_cast<Eigen::Index>(f), k) =
          index[static_cast<std::size_t>(kept[f][static_cast<std::size_t>(k)])];
  result.ok = true;
  return result;
}

/// A pseudo-random number in [−1, 1] from an integer (splitmix64): the same perturbation on
/// every run.
double hashed_unit(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return 2.0 * static_cast<double>(x >> 11) / static_cast<double>(1ULL << 53) - 1.0;
}

}  // namespace

WindingNumberBoundary winding_number_boundary(const Eigen::MatrixX3d& vertices,
                                              const Eigen::MatrixX3i& faces, bool refine) {
  WindingNumberBoundary first = label(vertices, faces, refine);
  if (first.ok || vertices.rows() == 0 || !refine)
    return first;
  // Sheets on each other, or a degenerate configuration CGAL does not handle: move every
  // vertex by a tiny pseudo-random amount and split again.
  const double size = (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
  Eigen::MatrixX3d moved = vertices;
  for (Eigen::Index i = 0; i < moved.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      moved(i, k) += kGenericPerturbation * size *
                     hashed_unit(3 * static_cast<std::uint64_t>(i) + static_cast<std::uint64_t>(k));
  WindingNumberBoundary second = label(moved, faces, true);
  second.perturbed = true;
  if (!second.ok)
    second.failure = first.failure + "; after a generic perturbation: " + second.failure;
  return second;
}

}  // namespace bemshape::geometry
