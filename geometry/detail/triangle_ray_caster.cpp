#include "geometry/detail/triangle_ray_caster.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace bemshape::geometry::detail {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr int kLeafSize = 4;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The barycentric tests accept points this far (relative) outside a piece, so that a ray
/// through a shared edge hits one of the two pieces despite rounding.
constexpr double kEdgeSlack = 1e-12;

/// Entry distance of the ray (o, 1/d) into the box [lo, hi]; +∞ if it misses.
double box_entry(const Vec3& o, const Vec3& inverse, const Vec3& lo, const Vec3& hi) {
  double near = 0.0, far = kInfinity;
  for (int k = 0; k < 3; ++k) {
    double t0 = (lo(k) - o(k)) * inverse(k), t1 = (hi(k) - o(k)) * inverse(k);
    if (t0 > t1)
      std::swap(t0, t1);
    // 0·∞ (a ray in the box's face plane) is NaN; max/min with NaN keep the other value.
    near = std::max(near, t0 == t0 ? t0 : near);
    far = std::min(far, t1 == t1 ? t1 : far);
  }
  return near <= far ? near : kInfinity;
}

}  // namespace

TriangleRayCaster::TriangleRayCaster(const Eigen::MatrixX3d& vertices,
                                     const Eigen::MatrixX3i& faces, double max_piece) {
  using Corners = std::array<Vec3, 3>;
  std::vector<Corners> stack;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    stack.push_back({vertices.row(faces(f, 0)).transpose(), vertices.row(faces(f, 1)).transpose(),
                     vertices.row(faces(f, 2)).transpose()});
    while (!stack.empty()) {
      const Corners c = stack.back();
      stack.pop_back();
      std::size_t longest = 0;
      double length = 0.0;
      for (std::size_t k = 0; k < 3; ++k)
        if (const double l = (c[(k + 1) % 3] - c[k]).norm(); l > length) {
          length = l;
          longest = k;
        }
      if (length > max_piece) {
        const Vec3 m = 0.5 * (c[longest] + c[(longest + 1) % 3]);
        stack.push_back({c[longest], m, c[(longest + 2) % 3]});
        stack.push_back({m, c[(longest + 1) % 3], c[(longest + 2) % 3]});
        continue;
      }
      const Vec3 ab = c[1] - c[0], ac = c[2] - c[0];
      if (ab.cross(ac).squaredNorm() == 0.0)
        continue;
      pieces_.push_back({c[0], ab, ac, f});
    }
  }
  if (!pieces_.empty())
    build(0, static_cast<int>(pieces_.size()));
}

int TriangleRayCaster::build(int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.begin = begin;
  node.end = end;
  node.lo = Vec3::Constant(kInfinity);
  node.hi = Vec3::Constant(-kInfinity);
  for (int i = begin; i < end; ++i) {
    const Piece& p = pieces_[static_cast<std::size_t>(i)];
    for (const Vec3& x : {p.a, Vec3(p.a + p.ab), Vec3(p.a + p.ac)}) {
      node.lo = node.lo.cwiseMin(x);
      node.hi = node.hi.cwiseMax(x);
    }
  }
  if (end - begin > kLeafSize) {
    int axis = 0;
    (node.hi - node.lo).maxCoeff(&axis);
    const int middle = begin + (end - begin) / 2;
    std::nth_element(pieces_.begin() + begin, pieces_.begin() + middle, pieces_.begin() + end,
                     [axis](const Piece& p, const Piece& q) {
                       return 3.0 * p.a(axis) + p.ab(axis) + p.ac(axis) <
                              3.0 * q.a(axis) + q.ab(axis) + q.ac(axis);
                     });
    node.left = build(begin, middle);
    node.right = build(middle, end);
  }
  nodes_[static_cast<std::size_t>(index)] = node;
  return index;
}

double TriangleRayCaster::first_hit(const Eigen::Vector3d& origin,
                                    const Eigen::Vector3d& direction,
                                    Eigen::Index skip_face, double max_distance) const {
  double best = max_distance;
  if (nodes_.empty())
    return best;
  const Vec3 inverse = direction.cwiseInverse();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
    if (box_entry(origin, inverse, node.lo, node.hi) >= best)
      continue;
    if (node.left >= 0) {
      // The child the ray enters first is searched first, so that its hits prune the other.
      const Node& l = nodes_[static_cast<std::size_t>(node.left)];
      const Node& r = nodes_[static_cast<std::size_t>(node.right)];
      const bool left_first = box_entry(origin, inverse, l.lo, l.hi) <=
                              box_entry(origin, inverse, r.lo, r.hi);
      stack[top++] = left_first ? node.right : node.left;
      stack[top++] = left_first ? node.left : node.right;
      continue;
    }
    for (int i = node.begin; i < node.end; ++i) {
      const Piece& p = pieces_[static_cast<std::size_t>(i)];
      if (p.face == skip_face)
        continue;
      // Möller–Trumbore: origin + t·d = a + u·ab + v·ac.
      const Vec3 q = direction.cross(p.ac);
      const double det = p.ab.dot(q);
      if (det == 0.0)
        continue;  // the ray runs parallel to the piece
      const double inv = 1.0 / det;
      const Vec3 s = origin - p.a;
      const double u = s.dot(q) * inv;
      if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack)
        continue;
      const Vec3 r = s.cross(p.ab);
      const double v = direction.dot(r) * inv;
      if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack)
        continue;
      const double t = p.ac.dot(r) * inv;
      if (t > 0.0 && t < best)
        best = t;
    }
  }
  return best < max_distance ? best : kInfinity;
}

}  // namespace bemshape::geometry::detail
