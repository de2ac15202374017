#include "geometry/mesh_size_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "core/errors.hpp"
#include "geometry/detail/triangle_ray_caster.hpp"
#include "geometry/union_find.hpp"

namespace bemshape::geometry {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Crease-spacing pieces are at most this fraction of the distance to the nearest other
/// crease; that distance changes by at most the piece's half length within it (it is
/// 1-Lipschitz), so the piece's size c_l·(l − L/2) is within 25 % of the exact one.
constexpr double kSpacingPieceFraction = 0.5;

/// The ray caster's pieces are at most this many sample spacings long: small boxes for the
/// tree, few pieces per sample.
constexpr double kRayPieceRatio = 4.0;

double segment_distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((x - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (x - (a + t * ab)).norm();
}

/// A point (a = b) or segment source of size h_s, growing away from it at `slope` (g − 1),
/// within h_s of it at `near_slope` ≤ slope (times the query's slope factor).
struct Source {
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  double size = 0.0;
  SizeReason reason = SizeReason::maximum;
  int end0 = -1, end1 = -1;  // corner vertices of a crease chain (exclusion in spacing queries)
  double slope = 1.0, near_slope = 1.0;
  /// h_s + near_slope·min(d, h_s) + slope·max(d − h_s, 0), at least h_s + near_slope·d.
  double value(double distance) const {
    if (near_slope == slope)
      return size + slope * distance;  // one gradation: the plain cone, rounded as such
    const double near = std::min(distance, size);
    return size + near_slope * near + slope * (distance - near);
  }
};

/// Bounding-volume tree over sources, for the lower envelope min_s (h_s + slope·dist(x, s)).
class SourceTree {
 public:
  SourceTree() = default;
  explicit SourceTree(std::vector<Source> sources) : sources_(std::move(sources)) {
    if (!sources_.empty())
      build(0, static_cast<int>(sources_.size()));
  }

  const std::vector<Source>& sources() const { return sources_; }

  /// min over sources s with keep(s) of Source::value(slope·dist(x, s)) (a slope factor of 1
  /// gives each source its own growth), if below `bound`: (value, index); else (bound, −1).
  template <class Keep>
  std::pair<double, int> envelope(const Vec3& x, double slope, double bound, Keep keep) const {
    std::pair<double, int> best{bound, -1};
    if (nodes_.empty())
      return best;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
      if (node.min_size + slope * node.min_slope * box_distance(x, node) >= best.first)
        continue;
      if (node.left < 0) {
        for (int i = node.begin; i < node.end; ++i) {
          const Source& s = sources_[static_cast<std::size_t>(i)];
          if (s.size >= best.first || !keep(s))
            continue;
          const double value = s.value(slope * segment_distance(x, s.a, s.b));
          if (value < best.first)
            best = {value, i};
        }
        continue;
      }
      const Node& l = nodes_[static_cast<std::size_t>(node.left)];
      const Node& r = nodes_[static_cast<std::size_t>(node.right)];
      const bool left_first = l.min_size + slope * l.min_slope * box_distance(x, l) <=
                              r.min_size + slope * r.min_slope * box_distance(x, r);
      // The nearer child is popped first. The depth is below 128 for any source count that
      // fits in memory: the tree is split at medians.
      stack[top++] = left_first ? node.right : node.left;
      stack[top++] = left_first ? node.left : node.right;
    }
    return best;
  }

 private:
  struct Node {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    double min_size = 0.0;
    double min_slope = 0.0;
    int begin = 0, end = 0;
    int left = -1, right = -1;
  };
  static constexpr int kLeafSize = 6;

  static double box_distance(const Vec3& x, const Node& node) {
    return (node.lo - x).cwiseMax(x - node.hi).cwiseMax(0.0).norm();
  }

  int build(int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.begin = begin;
    node.end = end;
    node.lo = Vec3::Constant(kInfinity);
    node.hi = Vec3::Constant(-kInfinity);
    node.min_size = kInfinity;
    node.min_slope = kInfinity;
    for (int i = begin; i < end; ++i) {
      const Source& s = sources_[static_cast<std::size_t>(i)];
      node.lo = node.lo.cwiseMin(s.a).cwiseMin(s.b);
      node.hi = node.hi.cwiseMax(s.a).cwiseMax(s.b);
      node.min_size = std::min(node.min_size, s.size);
      node.min_slope = std::min(node.min_slope, s.near_slope);
    }
    if (end - begin > kLeafSize) {
      int axis = 0;
      (node.hi - node.lo).maxCoeff(&axis);
      const int middle = begin + (end - begin) / 2;
      std::nth_element(sources_.begin() + begin, sources_.begin() + middle, sources_.begin() + end,
                       [axis](const Source& p, const Source& q) {
                         return p.a(axis) + p.b(axis) < q.a(axis) + q.b(axis);
                       });
      node.left = build(begin, middle);
      node.right = build(middle, end);
    }
    nodes_[static_cast<std::size_t>(index)] = node;
    return index;
  }

  std::vector<Source> sources_;
  std::vector<Node> nodes_;
};

/// A straight crease: a maximal chain of collinear crease edges between two corners.
struct CreaseChain {
  int corner0 = -1, corner1 = -1;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
};

std::vector<CreaseChain> crease_chains(const SurfaceMesh& mesh, const SurfaceCreases& creases) {
  const auto nv = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<std::vector<int>> adjacency(nv);
  for (const DihedralEdge& c : creases.creases) {
    adjacency[static_cast<std::size_t>(c.a)].push_back(c.b);
    adjacency[static_cast<std::size_t>(c.b)].push_back(c.a);
  }
  std::vector<CreaseChain> chains;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!creases.corner[v])
      continue;
    for (int w : adjacency[v]) {
      int previous = static_cast<int>(v), current = w;
      while (!creases.corner[static_cast<std::size_t>(current)]) {
        const auto& next = adjacency[static_cast<std::size_t>(current)];
        const int following = next[0] == previous ? next[1] : next[0];
        previous = current;
        current = following;
      }
      // Each chain is found from both ends; keep it once (and a chain from a corner to
      // itself, which cannot be straight, never arises: such loops have a turning vertex).
      if (static_cast<int>(v) < current || (static_cast<int>(v) == current && w < previous))
        chains.push_back({static_cast<int>(v), current, mesh.vertices().row(static_cast<Eigen::Index>(v)),
                          mesh.vertices().row(current)});
    }
  }
  return chains;
}

}  // namespace

const char* to_string(SizeReason reason) {
  switch (reason) {
    case SizeReason::maximum:
      return "maximum";
    case SizeReason::crease:
      return "crease";
    case SizeReason::crease_spacing:
      return "crease spacing";
    case SizeReason::thin_wall:
      return "thin wall";
    case SizeReason::wall_thickness:
      return "wall thickness";
    case SizeReason::curvature:
      return "curvature";
    case SizeReason::chord:
      return "chord";
  }
  return "?";
}

struct MeshSizeField::Impl {
  double max_edge = 0.0;
  double gradation = 1.0;
  SourceTree tree;
  SizeFieldSummary summary;
};

MeshSizeField::MeshSizeField(double size) : impl_(std::make_unique<Impl>()) {
  if (!(std::isfinite(size) && size > 0.0))
    throw InputError("size field: the element size must be a positive length, got " +
                     std::to_string(size));
  impl_->max_edge = size;
  impl_->gradation = 1.0;
  impl_->summary.min_size = size;
}

MeshSizeField::MeshSizeField(const SurfaceMesh& mesh, const SurfaceCreases& creases,
                             const SizeFieldParameters& p)
    : impl_(std::make_unique<Impl>()) {
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(p.fine_edge) || !positive(p.max_edge) || p.fine_edge > p.max_edge ||
      !(std::isfinite(p.gradation) && p.gradation > 1.0) || !positive(p.crease_spacing_ratio) ||
      (p.thin_wall > 0.0 && (!positive(p.sample_spacing) || !positive(p.wall_thickness_ratio)))) {
    std::ostringstream msg;
    msg << "size field: need 0 < h_f ≤ h_max, g > 1 and positive ratios (h_f " << p.fine_edge
        << ", h_max " << p.max_edge << ", g " << p.gradation << ")";
    throw InputError(msg.str());
  }
  if (mesh.empty())
    throw InputError("size field: the mesh is empty");
  Impl& s = *impl_;
  s.max_edge = p.max_edge;
  s.gradation = p.gradation;
  const double curvature_gradation =
      p.curvature_gradation > 0.0 ? std::min(p.curvature_gradation, p.gradation) : p.gradation;
  const double floor = p.min_size > 0.0 ? p.min_size : kMinSizeRatio * p.fine_edge;
  const Eigen::MatrixX3d& V = mesh.vertices();

  std::vector<Source> sources;
  auto add = [&](const Vec3& a, const Vec3& b, double size, SizeReason reason) {
    size = std::max(size, floor);
    const double near_g = reason == SizeReason::curvature ? curvature_gradation : p.gradation;
    if (size < p.max_edge)
      sources.push_back({a, b, size, reason, -1, -1, p.gradation - 1.0, near_g - 1.0});
  };

  // Creases: h_f, or for the facet creases of a tessellated smooth surface the curvature rule.
  for (const DihedralEdge& c : creases.creases) {
    const Vec3 a = V.row(c.a), b = V.row(c.b);
    if (c.tessellated && p.curvature_ratio > 0.0)
      add(a, b, std::max(p.fine_edge, p.curvature_ratio * c.facet_width / c.angle),
          SizeReason::curvature);
    else if (p.refine_creases)
      add(a, b, p.fine_edge, SizeReason::crease);
  }

  // The inward direction of the wall-thickness rays: the normals the creases were found with
  // (filtered at a scale on a noisy surface, surface_creases.hpp), else the faces' own.
  const Eigen::MatrixX3d& normals =
      creases.normals.rows() == mesh.num_faces() ? creases.normals : mesh.face_normals();
  // A ray's first hit nearer than this is the surface's own roughness, not a wall (a thin
  // wall is one thinner than t_thin; a tenth of that is below what the PDE resolves there).
  const double min_wall = kMinWallRatio * p.thin_wall;
  // Rays along −n against the surface: the wall-thickness estimate of the thin-wall, wall-
  // thickness and (with c_δ) chord sources.
  const bool chord_from_wall = p.chord_thickness_ratio > 0.0 && p.sample_spacing > 0.0;
  std::unique_ptr<detail::TriangleRayCaster> rays;
  if (p.thin_wall > 0.0 || chord_from_wall)
    rays = std::make_unique<detail::TriangleRayCaster>(mesh.vertices(), mesh.faces(),
                                                       kRayPieceRatio * p.sample_spacing);
  // Walls thicker than this set no size below h_max.
  const double reach = std::max(p.thin_wall, p.max_edge / p.wall_thickness_ratio);

  // Curvature and chord limits of the edges the remesher crosses.
  std::vector<double> chord(creases.crossed.size());
  for (std::size_t i = 0; i < chord.size(); ++i) chord[i] = creases.crossed[i].max_chord;
  if (chord_from_wall) {
    // The wall under the edge: the thinner of the rays from its two faces' centroids. A
    // chord of length h across the edge then sags by at most c_δ·wall; beyond the reach of
    // the rays (no wall within h_max/c_t) by at most c_δ·reach.
    auto wall_under = [&](int f) {
      const Vec3 n = normals.row(f);
      const Vec3 start = mesh.face_centroids().row(f).transpose() - min_wall * n;
      return min_wall + rays->first_hit(start, -n, f, reach);
    };
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < chord.size(); ++i) {
      const CrossedEdge& e = creases.crossed[i];
      const double wall = std::min({wall_under(e.f0), wall_under(e.f1), reach});
      chord[i] = longest_chord_within(e.angle, e.facet_width, p.chord_thickness_ratio * wall);
    }
  }
  for (std::size_t i = 0; i < chord.size(); ++i) {
    const CrossedEdge& e = creases.crossed[i];
    const Vec3 a = V.row(e.a), b = V.row(e.b);
    const double curvature = p.curvature_ratio > 0.0
                                 ? std::max(p.fine_edge, p.curvature_ratio * e.facet_width / e.angle)
                                 : kInfinity;
    if (chord[i] < curvature)
      add(a, b, chord[i], SizeReason::chord);
    else
      add(a, b, curvature, SizeReason::curvature);
  }

  // Crease spacing: distance from each straight crease to the nearest one sharing no corner,
  // and the shortest straight crease at each corner.
  {
    const std::vector<CreaseChain> chains = crease_chains(mesh, creases);
    std::vector<Source> chain_sources;
    chain_sources.reserve(chains.size());
    std::vector<double> corner_spacing(static_cast<std::size_t>(mesh.num_vertices()), kInfinity);
    // The straight pieces of one curved crease (a tessellated rim, joined at its curved
    // vertices) are one crease: neither their lengths nor their distances to each other
    // bound the size; its chords are limited by the chord sources above.
    auto curved = [&](int v) {
      return !creases.curved.empty() && creases.curved[static_cast<std::size_t>(v)];
    };
    UnionFind curves(static_cast<std::size_t>(mesh.num_vertices()));
    for (const CreaseChain& c : chains)
      if (curved(c.corner0) || curved(c.corner1))
        curves.unite(c.corner0, c.corner1);
    auto curve_of = [&](int end0, int end1) {
      return curved(end0) || curved(end1) ? curves.find(end0) : -1;
    };
    for (const CreaseChain& c : chains) {
      chain_sources.push_back({c.a, c.b, 0.0, SizeReason::crease_spacing, c.corner0, c.corner1, 1.0, 1.0});
      const double length = (c.b - c.a).norm();
      for (int corner : {c.corner0, c.corner1})
        if (!curved(corner))
          corner_spacing[static_cast<std::size_t>(corner)] =
              std::min(corner_spacing[static_cast<std::size_t>(corner)], length);
    }
    for (std::size_t v = 0; v < corner_spacing.size(); ++v)
      if (std::isfinite(corner_spacing[v]))
        add(V.row(static_cast<Eigen::Index>(v)), V.row(static_cast<Eigen::Index>(v)),
            p.crease_spacing_ratio * corner_spacing[v], SizeReason::crease_spacing);
    const SourceTree chain_tree(std::move(chain_sources));
    const double reach = p.max_edge / p.crease_spacing_ratio;  // farther creases do not matter
    for (const CreaseChain& c : chains) {
      const int curve = curve_of(c.corner0, c.corner1);
      auto other = [&](const Source& s) {
        return s.end0 != c.corner0 && s.end0 != c.corner1 && s.end1 != c.corner0 &&
               s.end1 != c.corner1 && (curve < 0 || curve_of(s.end0, s.end1) != curve);
      };
      std::vector<std::pair<Vec3, Vec3>> pieces{{c.a, c.b}};
      while (!pieces.empty()) {
        const auto [a, b] = pieces.back();
        pieces.pop_back();
        const Vec3 middle = 0.5 * (a + b);
        const double half = 0.5 * (b - a).norm();
        const double spacing = chain_tree.envelope(middle, 1.0, reach + half, other).first;
        if (spacing >= reach + half)
          continue;
        if (half <= 0.5 * kSpacingPieceFraction * spacing || half <= floor)
          add(a, b, p.crease_spacing_ratio * std::max(spacing - half, 0.0),
              SizeReason::crease_spacing);
        else {
          pieces.emplace_back(a, middle);
          pieces.emplace_back(middle, b);
        }
      }
    }
  }

  // Wall thickness: a ray along −n from sample points about sample_spacing apart: the
  // centroids of the faces' pieces (longest edge first) no longer than the spacing, one per
  // cell of a grid of that spacing and per direction of the normal (so that the two sides of
  // a wall thinner than a cell keep a sample each; a fan of CAD slivers would otherwise give
  // hundreds of samples per cell).
  if (p.thin_wall > 0.0) {
    struct Sample {
      Vec3 x, n;
      Eigen::Index face;
    };
    std::vector<Sample> samples;
    std::unordered_map<std::uint64_t, std::size_t> cell_sample;
    const Vec3 origin = mesh.bounding_box().min;
    auto key = [&](const Vec3& x, const Vec3& n) {
      const Eigen::Array3i c = ((x - origin) / p.sample_spacing).array().floor().cast<int>();
      const Eigen::Array3i d = (2.0 * n).array().round().cast<int>() + 2;  // 0..4 each
      std::uint64_t k = 0;
      for (int j = 0; j < 3; ++j)
        k = k * 2097152u + static_cast<std::uint64_t>(c(j) & 0x1FFFFF);
      return k * 125u + static_cast<std::uint64_t>(d(0) * 25 + d(1) * 5 + d(2));
    };
    for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
      const Vec3 n = normals.row(f);
      if (n.squaredNorm() == 0.0)
        continue;
      std::vector<std::array<Vec3, 3>> stack{{mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)}};
      while (!stack.empty()) {
        const auto t = stack.back();
        stack.pop_back();
        std::size_t longest = 0;
        double length = 0.0;
        for (std::size_t k = 0; k < 3; ++k)
          if (const double l = (t[(k + 1) % 3] - t[k]).norm(); l > length) {
            length = l;
            longest = k;
          }
        if (length > p.sample_spacing) {
          const Vec3 m = 0.5 * (t[longest] + t[(longest + 1) % 3]);
          stack.push_back({t[longest], m, t[(longest + 2) % 3]});
          stack.push_back({m, t[(longest + 1) % 3], t[(longest + 2) % 3]});
          continue;
        }
        const Vec3 x = (t[0] + t[1] + t[2]) / 3.0;
        if (cell_sample.try_emplace(key(x, n), samples.size()).second)
          samples.push_back({x, n, f});
      }
    }
    std::vector<double> wall(samples.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < samples.size(); ++i)
      wall[i] = min_wall + rays->first_hit(samples[i].x - min_wall * samples[i].n, -samples[i].n,
                                           samples[i].face, reach);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (!std::isfinite(wall[i]))
        continue;
      const bool thin = wall[i] < p.thin_wall;
      add(samples[i].x, samples[i].x, thin ? p.fine_edge : p.wall_thickness_ratio * wall[i],
          thin ? SizeReason::thin_wall : SizeReason::wall_thickness);
    }
  }

  SizeFieldSummary& summary = s.summary;
  summary.smallest.fill(kInfinity);
  summary.smallest[0] = p.max_edge;
  summary.min_size = p.max_edge;
  for (const Source& source : sources) {
    const auto r = static_cast<std::size_t>(source.reason);
    ++summary.sources[r];
    summary.smallest[r] = std::min(summary.smallest[r], source.size);
    summary.min_size = std::min(summary.min_size, source.size);
  }
  s.tree = SourceTree(std::move(sources));
}

MeshSizeField::~MeshSizeField() = default;
MeshSizeField::MeshSizeField(MeshSizeField&&) noexcept = default;
MeshSizeField& MeshSizeField::operator=(MeshSizeField&&) noexcept = default;

std::pair<double, SizeReason> MeshSizeField::size_and_reason(const Eigen::Vector3d& x) const {
  const auto [value, index] =
      impl_->tree.envelope(x, 1.0, impl_->max_edge,  // each source's own growth
                           [](const Source&) { return true; });
  if (index < 0)
    return {impl_->max_edge, SizeReason::maximum};
  return {value, impl_->tree.sources()[static_cast<std::size_t>(index)].reason};
}

double MeshSizeField::max_edge() const { return impl_->max_edge; }
double MeshSizeField::gradation() const { return impl_->gradation; }
const SizeFieldSummary& MeshSizeField::summary() const { return impl_->summary; }

}  // namespace bemshape::geometry
