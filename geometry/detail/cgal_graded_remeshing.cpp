// The translation unit that compiles the graded remesher on CGAL's Surface_mesh.
//
// Botsch & Kobbelt, "A remeshing approach to multiresolution modeling" (SGP 2004), with the
// target length a field h(x): split edges longer than 4/3·h, collapse edges shorter than
// 4/5·h, flip towards the ideal valences, relax tangentially, put the vertices back onto the
// input surface. Creases are kept exactly: a crease edge is only split at its midpoint (a
// point of the input's straight crease), a vertex inside a straight crease only slides along
// it or is collapsed into a neighbour on the same crease, crease corners never move, and a
// crease edge is never flipped. Every free vertex stays on the input faces of its patch (the
// faces between creases), so the union of the output faces is the input surface (where all
// candidate creases are kept) or within the chord tolerance of it (where facets of a smooth
// tessellation are crossed).
//
// Quality guards: splits are always made (the size field asks for them); a collapse, flip or
// move is made only if no face it creates has a normal turned by more than max_normal_turn
// from the face it replaces, none is degenerate, and the smallest angle of the faces it
// creates is at least min(min_angle, the smallest angle of the faces it removes) — an
// operation may improve a bad triangle, never make a good one bad.
#include "geometry/detail/cgal_graded_remeshing.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::geometry::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VertexIndex = Mesh::Vertex_index;
using HalfedgeIndex = Mesh::Halfedge_index;
using EdgeIndex = Mesh::Edge_index;
using FaceIndex = Mesh::Face_index;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Segment = Kernel::Segment_3;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, std::vector<Segment>::const_iterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;
using Vec3 = Eigen::Vector3d;

/// Botsch–Kobbelt thresholds: split above 4/3·h, collapse below 4/5·h (their midpoint is
/// about h, and a split edge's halves are not immediately collapsed, nor a collapse's new
/// edges immediately split).
constexpr double kSplitRatio = 4.0 / 3.0;
constexpr double kCollapseRatio = 4.0 / 5.0;
/// Split passes per iteration: each halves the longest edges, so an edge 2^k times too long
/// needs k; CAD slivers 10^3 times longer than h need 10.
constexpr int kMaxSplitPasses = 40;
/// Passes of Lawson's Delaunay flips at the start (each pass flips every edge that is not
/// locally Delaunay once; a plate's CAD slivers need a few dozen).
constexpr int kDelaunayPasses = 100;
/// Margin [rad] by which the opposite angles must exceed π for a Delaunay flip.
constexpr double kDelaunayMargin = 1e-9;
/// Flip passes per iteration (a flip changes the valences the next flip sees).
constexpr int kFlipPasses = 3;
/// Rescue of the faces below the angle bound after the iterations: passes, the edge length a
/// rescuing collapse may leave (relative to h; the collapse must improve the worst angle
/// around it), and the positions tried along a crease.
constexpr int kRescuePasses = 4;
constexpr double kRescueLengthRatio = 1.6;
constexpr int kRescueSamples = 20;
/// A patch whose input faces are coplanar to this tolerance [rad, and fraction of the
/// diagonal for the offsets] is projected onto its plane instead of through an AABB tree.
constexpr double kCoplanarTolerance = 1e-12;
/// A moved vertex's size is evaluated again after it moved by this fraction of it.
constexpr double kSizeRefresh = 0.05;

enum VertexKind : unsigned char { kFree = 0, kChain = 1, kCorner = 2 };

Vec3 vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
Point point(const Vec3& x) { return Point(x(0), x(1), x(2)); }

/// Smallest interior angle [rad] of the triangle (a, b, c); 0 if degenerate.
double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e[3] = {b - a, c - b, a - c};
  const double l2[3] = {e[0].squaredNorm(), e[1].squaredNorm(), e[2].squaredNorm()};
  const double cross = e[0].cross(e[2]).norm();  // twice the area
  if (!(cross > 0.0))
    return 0.0;
  // The smallest angle is opposite the shortest edge: sin = 2A / (product of the other two).
  int shortest = 0;
  for (int k = 1; k < 3; ++k)
    if (l2[k] < l2[shortest])
      shortest = k;
  const double others = std::sqrt(l2[(shortest + 1) % 3] * l2[(shortest + 2) % 3]);
  return std::asin(std::min(1.0, cross / others));
}

Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

/// Where a free vertex of a patch is put back onto the input: the plane of a flat patch, or
/// the closest point of the patch's input faces.
class PatchSurface {
 public:
  void add(const Triangle& t) { triangles_.push_back(t); }
  void finish(double diagonal) {
    const Vec3 a = vec(triangles_.front()[0]);
    normal_ = unit_normal(a, vec(triangles_.front()[1]), vec(triangles_.front()[2]));
    flat_ = normal_.squaredNorm() > 0.0;
    for (const Triangle& t : triangles_) {
      if (!flat_)
        break;
      const Vec3 n = unit_normal(vec(t[0]), vec(t[1]), vec(t[2]));
      if (n.squaredNorm() == 0.0)
        continue;  // a zero-area input face lies on its neighbours' plane
      if (n.cross(normal_).norm() > kCoplanarTolerance || n.dot(normal_) < 0.0)
        flat_ = false;
      for (int k = 0; k < 3 && flat_; ++k)
        if (std::abs((vec(t[k]) - a).dot(normal_)) > kCoplanarTolerance * diagonal)
          flat_ = false;
    }
    origin_ = a;
    if (!flat_) {
      tree_ = std::make_unique<Tree>(triangles_.begin(), triangles_.end());
      tree_->accelerate_distance_queries();
    }
  }
  bool flat() const { return flat_; }
  Vec3 project(const Vec3& x) const {
    if (flat_)
      return x - normal_ * (x - origin_).dot(normal_);
    return vec(tree_->closest_point(point(x)));
  }

 private:
  std::vector<Triangle> triangles_;
  std::unique_ptr<Tree> tree_;
  Vec3 normal_ = Vec3::Zero(), origin_ = Vec3::Zero();
  bool flat_ = false;
};

class Remesher {
 public:
  explicit Remesher(const GradedRemeshInput& input) : in_(input) { build(); }

  GradedRemeshOutput run() {
    const unsigned iterations = std::max(in_.iterations, 1u);
    const double steps = iterations + 1.0;
    // Start from the creases at their size and a Delaunay triangulation of them: splitting
    // the long edges of CAD slivers directly cascades (a 128-facet tube's 80 mm strips took a
    // million splits and as many collapses), while a strip between two split creases is
    // already triangulated well by its Delaunay flips.
    split_long_edges(true);
    delaunay_flips();
    for (unsigned it = 0; it < iterations; ++it) {
      split_long_edges();
      collapse_short_edges();
      flip_until_settled(kFlipPasses, false);
      relax();
      progress((it + 1) / steps);
    }
    // Finish: the last relaxation may have left edges above the split bound and flips that
    // improve a bad triangle; split, then rescue the angles without changing the sizes.
    split_long_edges();
    flip_until_settled(2 * kFlipPasses, true);
    relax();
    flip_until_settled(2 * kFlipPasses, true);
    rescue();
    if (in_.max_edge_ratio > 0.0) {
      split_long_edges(false, in_.max_edge_ratio);
      flip_until_settled(2 * kFlipPasses, true);
      // A midpoint split of a good triangle's longest edge can halve one of its angles;
      // rescue those with collapses that keep every edge within the bound.
      rescue(std::min(kRescueLengthRatio, in_.max_edge_ratio));
    }
    progress(1.0);
    return output();
  }

 private:
  // ---- set-up ----------------------------------------------------------------------------

  void build() {
    const Eigen::MatrixX3d& V = *in_.vertices;
    const Eigen::MatrixX3i& F = *in_.faces;
    std::vector<VertexIndex> vh(static_cast<std::size_t>(V.rows()));
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      vh[static_cast<std::size_t>(v)] = mesh_.add_vertex(point(V.row(v).transpose()));
    kind_ = mesh_.add_property_map<VertexIndex, unsigned char>("v:kind", kFree).first;
    vpatch_ = mesh_.add_property_map<VertexIndex, int>("v:patch", -1).first;
    size_ = mesh_.add_property_map<VertexIndex, double>("v:size", 0.0).first;
    sized_at_ = mesh_.add_property_map<VertexIndex, Vec3>("v:sized_at", Vec3::Zero()).first;
    crease_ = mesh_.add_property_map<EdgeIndex, bool>("e:crease", false).first;
    fpatch_ = mesh_.add_property_map<FaceIndex, int>("f:patch", -1).first;
    valence_target_ = mesh_.add_property_map<VertexIndex, int>("v:valence", 6).first;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const FaceIndex fi = mesh_.add_face(vh[static_cast<std::size_t>(F(f, 0))],
                                          vh[static_cast<std::size_t>(F(f, 1))],
                                          vh[static_cast<std::size_t>(F(f, 2))]);
      if (fi == Mesh::null_face())
        throw InputError("graded remeshing needs a closed manifold surface (face " +
                         std::to_string(f) + " is not manifold); prepare the mesh first");
      fpatch_[fi] = (*in_.face_patch)(f);
    }
    if (!CGAL::is_closed(mesh_))
      throw InputError("graded remeshing needs a closed surface; prepare the mesh first");
    for (const auto& c : in_.creases) {
      const HalfedgeIndex h = mesh_.halfedge(vh[static_cast<std::size_t>(c[0])],
                                             vh[static_cast<std::size_t>(c[1])]);
      if (h == Mesh::null_halfedge())
        throw InternalError("graded remeshing: a crease is not an edge of the mesh");
      crease_[mesh_.edge(h)] = true;
      if (in_.curved_creases)
        crease_segments_.emplace_back(point(V.row(c[0]).transpose()), point(V.row(c[1]).transpose()));
    }
    if (in_.curved_creases && !crease_segments_.empty()) {
      crease_tree_ = std::make_unique<SegmentTree>(crease_segments_.begin(), crease_segments_.end());
      crease_tree_->accelerate_distance_queries();
    }
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      const VertexIndex vi = vh[static_cast<std::size_t>(v)];
      if ((*in_.corner)[static_cast<std::size_t>(v)])
        kind_[vi] = kCorner;
      else {
        for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh_.halfedge(vi), mesh_))
          if (crease_[mesh_.edge(h)])
            kind_[vi] = kChain;
      }
      vpatch_[vi] = fpatch_[mesh_.face(mesh_.halfedge(vi))];
    }
    // The sizes at the input's vertices, in parallel (the size field's queries are const).
    std::vector<double> sizes(static_cast<std::size_t>(V.rows()));
#pragma omp parallel for schedule(dynamic, 256)
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      sizes[static_cast<std::size_t>(v)] = in_.size(V.row(v).transpose());
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      const VertexIndex vi = vh[static_cast<std::size_t>(v)];
      size_[vi] = sizes[static_cast<std::size_t>(v)];
      sized_at_[vi] = V.row(v).transpose();
    }
    // The input surface of each patch.
    double diagonal = 0.0;
    {
      const Vec3 lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
      diagonal = (hi - lo).norm();
    }
    surfaces_.resize(static_cast<std::size_t>(in_.patches));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      surfaces_[static_cast<std::size_t>((*in_.face_patch)(f))].add(
          Triangle(point(V.row(F(f, 0)).transpose()), point(V.row(F(f, 1)).transpose()),
                   point(V.row(F(f, 2)).transpose())));
    for (PatchSurface& s : surfaces_)
      s.finish(diagonal);
    cos_turn_ = std::cos(in_.max_normal_turn);
  }

  void progress(double fraction) {
    if (in_.progress)
      in_.progress(fraction);
  }

  // ---- geometry --------------------------------------------------------------------------

  Vec3 pos(VertexIndex v) const { return vec(mesh_.point(v)); }
  /// A point for a crease vertex: x itself on straight creases (x lies on the line of the
  /// crease already), the closest point of the input's crease polygon where creases curve.
  Vec3 on_crease(const Vec3& x) const {
    return crease_tree_ ? vec(crease_tree_->closest_point(point(x))) : x;
  }
  double target(VertexIndex a, VertexIndex b) const { return 0.5 * (size_[a] + size_[b]); }
  double length(HalfedgeIndex h) const {
    return (pos(mesh_.target(h)) - pos(mesh_.source(h))).norm();
  }
  double face_min_angle(FaceIndex f) const {
    const HalfedgeIndex h = mesh_.halfedge(f);
    return min_angle(pos(mesh_.source(h)), pos(mesh_.target(h)),
                     pos(mesh_.target(mesh_.next(h))));
  }
  Vec3 face_normal(FaceIndex f) const {
    const HalfedgeIndex h = mesh_.halfedge(f);
    return unit_normal(pos(mesh_.source(h)), pos(mesh_.target(h)),
                       pos(mesh_.target(mesh_.next(h))));
  }
  /// Moves v to x; its size is evaluated again once it has moved by kSizeRefresh of it since
  /// the last evaluation (h is (g − 1)-Lipschitz, so the cached value is then within
  /// (g − 1)·kSizeRefresh of h(x)).
  void set_position(VertexIndex v, const Vec3& x) {
    mesh_.point(v) = point(x);
    if ((x - sized_at_[v]).norm() > kSizeRefresh * size_[v]) {
      size_[v] = in_.size(x);
      sized_at_[v] = x;
    }
  }

  /// Is the triangle (a, b, c), replacing a face of unit normal `old_normal` whose angles
  /// were at least `old_min`, acceptable?
  bool acceptable(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& old_normal,
                  double old_min) const {
    const Vec3 n = unit_normal(a, b, c);
    if (n.squaredNorm() == 0.0 || n.dot(old_normal) < cos_turn_)
      return false;
    return min_angle(a, b, c) >= std::min(in_.min_angle, old_min);
  }

  // ---- split -----------------------------------------------------------------------------

  /// Splits every edge longer than kSplitRatio·h (only the crease edges if creases_only)
  /// until none is left.
  void split_long_edges(bool creases_only = false, double ratio_bound = kSplitRatio) {
    for (int pass = 0; pass < kMaxSplitPasses; ++pass) {
      std::vector<std::pair<double, EdgeIndex>> long_edges;
      for (EdgeIndex e : mesh_.edges()) {
        if (creases_only && !crease_[e])
          continue;
        const HalfedgeIndex h = mesh_.halfedge(e);
        const double ratio =
            length(h) / target(mesh_.source(h), mesh_.target(h));
        if (ratio > ratio_bound)
          long_edges.emplace_back(ratio, e);
      }
      if (long_edges.empty())
        return;
      if (static_cast<double>(mesh_.number_of_faces() + 2 * long_edges.size()) > in_.max_faces) {
        std::ostringstream msg;
        msg << "the graded solver mesh would exceed " << std::llround(in_.max_faces)
            << " faces; choose a larger element size (h0 or --max-edge)";
        throw ResourceError(msg.str());
      }
      std::sort(long_edges.begin(), long_edges.end(),
                [](const auto& p, const auto& q) { return p.first > q.first; });
      // The new vertices' positions and sizes first, in parallel: a split moves no vertex,
      // so every listed edge keeps its ends until it is split itself.
      const auto count = static_cast<std::ptrdiff_t>(long_edges.size());
      std::vector<Vec3> points(long_edges.size());
      std::vector<double> sizes(long_edges.size());
#pragma omp parallel for schedule(dynamic, 64)
      for (std::ptrdiff_t i = 0; i < count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        points[k] = split_point(long_edges[k].second);
        sizes[k] = in_.size(points[k]);
      }
      for (std::size_t k = 0; k < long_edges.size(); ++k)
        split(long_edges[k].second, points[k], sizes[k]);
    }
  }

  /// Where split puts the new vertex of edge e: its midpoint, projected onto the patch of the
  /// edge's first face or onto the crease.
  Vec3 split_point(EdgeIndex e) const {
    const HalfedgeIndex h = mesh_.halfedge(e);
    const int patch0 = fpatch_[mesh_.face(h)];
    const Vec3 x = 0.5 * (pos(mesh_.source(h)) + pos(mesh_.target(h)));
    if (crease_[e]) return on_crease(x);
    if (!surfaces_[static_cast<std::size_t>(patch0)].flat())
      return surfaces_[static_cast<std::size_t>(patch0)].project(x);
    return x;
  }

  /// Splits e at x (split_point(e)), whose size is `size`.
  void split(EdgeIndex e, const Vec3& x, double size) {
    const HalfedgeIndex h = mesh_.halfedge(e);
    const bool crease = crease_[e];
    const FaceIndex f0 = mesh_.face(h), f1 = mesh_.face(mesh_.opposite(h));
    const int patch0 = fpatch_[f0], patch1 = fpatch_[f1];
    // hnew: a → v, followed by h: v → b.
    const HalfedgeIndex hnew = CGAL::Euler::split_edge(h, mesh_);
    const VertexIndex v = mesh_.target(hnew);
    crease_[mesh_.edge(hnew)] = crease;
    kind_[v] = crease ? kChain : kFree;
    vpatch_[v] = patch0;
    mesh_.point(v) = point(x);
    size_[v] = size;
    sized_at_[v] = x;
    // The two quadrilaterals (a, v, b, c) and (b, v, a, d) become two triangles each.
    const HalfedgeIndex top = CGAL::Euler::split_face(hnew, mesh_.next(mesh_.next(hnew)), mesh_);
    fpatch_[mesh_.face(top)] = patch0;
    fpatch_[mesh_.face(mesh_.opposite(top))] = patch0;
    const HalfedgeIndex opposite = mesh_.opposite(h);  // b → v
    const HalfedgeIndex bottom =
        CGAL::Euler::split_face(opposite, mesh_.next(mesh_.next(opposite)), mesh_);
    fpatch_[mesh_.face(bottom)] = patch1;
    fpatch_[mesh_.face(mesh_.opposite(bottom))] = patch1;
    ++splits_;
  }

  // ---- collapse --------------------------------------------------------------------------

  /// Can `remove` be collapsed into `keep` along the edge of halfedge h (remove → keep)?
  /// Returns the smallest angle of the faces the collapse makes, or −1 if it may not.
  double collapse_quality(HalfedgeIndex h, double length_ratio = kSplitRatio) const {
    const VertexIndex remove = mesh_.source(h), keep = mesh_.target(h);
    const EdgeIndex e = mesh_.edge(h);
    if (kind_[remove] == kCorner || (kind_[remove] == kChain && !crease_[e]))
      return -1.0;
    const Vec3 x = pos(keep);
    const HalfedgeIndex into_remove = mesh_.opposite(h);
    double old_min = std::numeric_limits<double>::infinity();
    for (FaceIndex f : CGAL::faces_around_target(into_remove, mesh_))
      old_min = std::min(old_min, face_min_angle(f));
    double new_min = std::numeric_limits<double>::infinity();
    const FaceIndex removed0 = mesh_.face(h), removed1 = mesh_.face(into_remove);
    for (HalfedgeIndex g : CGAL::halfedges_around_target(into_remove, mesh_)) {
      // g ends at `remove`; its face (g, next(g), prev(g)) has corners source(g), remove,
      // target(next(g)).
      const FaceIndex f = mesh_.face(g);
      if (f == removed0 || f == removed1)
        continue;
      const VertexIndex p = mesh_.source(g), q = mesh_.target(mesh_.next(g));
      const Vec3 a = pos(p), c = pos(q);
      if (!acceptable(a, x, c, face_normal(f), old_min))
        return -1.0;
      new_min = std::min(new_min, min_angle(a, x, c));
      // The new edges keep → p must not be too long.
      if ((a - x).norm() > length_ratio * target(keep, p))
        return -1.0;
    }
    if (!CGAL::Euler::does_satisfy_link_condition(e, mesh_))
      return -1.0;
    return new_min;
  }

  void collapse_short_edges() {
    std::vector<std::pair<double, EdgeIndex>> short_edges;
    for (EdgeIndex e : mesh_.edges()) {
      const HalfedgeIndex h = mesh_.halfedge(e);
      const double ratio = length(h) / target(mesh_.source(h), mesh_.target(h));
      if (ratio < kCollapseRatio)
        short_edges.emplace_back(ratio, e);
    }
    std::sort(short_edges.begin(), short_edges.end(),
              [](const auto& p, const auto& q) { return p.first < q.first; });
    for (const auto& [ratio, e] : short_edges) {
      if (mesh_.is_removed(e))
        continue;
      const HalfedgeIndex h = mesh_.halfedge(e);
      if (length(h) >= kCollapseRatio * target(mesh_.source(h), mesh_.target(h)))
        continue;  // an earlier collapse moved its ends
      const double forward = collapse_quality(h);
      const double backward = collapse_quality(mesh_.opposite(h));
      if (forward < 0.0 && backward < 0.0)
        continue;
      collapse(forward >= backward ? h : mesh_.opposite(h));
    }
    mesh_.collect_garbage();
  }

  /// Collapses source(h) into target(h).
  void collapse(HalfedgeIndex h) {
    const VertexIndex remove = mesh_.source(h), keep = mesh_.target(h);
    const VertexIndex top = mesh_.target(mesh_.next(h));
    const VertexIndex bottom = mesh_.target(mesh_.next(mesh_.opposite(h)));
    // Two edges merge on each side; the merged edge is a crease if either was.
    const bool top_crease = crease_[mesh_.edge(mesh_.next(h))] ||
                            crease_[mesh_.edge(mesh_.prev(h))];
    const bool bottom_crease = crease_[mesh_.edge(mesh_.next(mesh_.opposite(h)))] ||
                               crease_[mesh_.edge(mesh_.prev(mesh_.opposite(h)))];
    const Point x = mesh_.point(keep);
    const unsigned char kind = kind_[keep];
    const int patch = vpatch_[keep];
    const double size = size_[keep];
    const Vec3 sized_at = sized_at_[keep];
    const VertexIndex kept = CGAL::Euler::collapse_edge(mesh_.edge(h), mesh_);
    mesh_.point(kept) = x;
    kind_[kept] = kind;
    vpatch_[kept] = patch;
    size_[kept] = size;
    sized_at_[kept] = sized_at;
    crease_[mesh_.edge(mesh_.halfedge(kept, top))] = top_crease;
    crease_[mesh_.edge(mesh_.halfedge(kept, bottom))] = bottom_crease;
    (void)remove;
    ++collapses_;
  }

  // ---- flip ------------------------------------------------------------------------------

  /// Ideal valence of a vertex: its total angle over 60°, at least 3 (6 inside a flat patch
  /// or on a straight crease, 4 or 5 at a box corner).
  int ideal_valence(VertexIndex v) const {
    double total = 0.0;
    for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_)) {
      const Vec3 a = pos(mesh_.source(h)), b = pos(v), c = pos(mesh_.target(mesh_.next(h)));
      const Vec3 u = a - b, w = c - b;
      total += std::atan2(u.cross(w).norm(), u.dot(w));
    }
    return std::max(3, static_cast<int>(std::lround(total / (std::numbers::pi / 3.0))));
  }

  /// Passes of flip_edges until one flips nothing, at most `max_passes`.
  void flip_until_settled(int max_passes, bool rescue_only) {
    for (int pass = 0; pass < max_passes; ++pass)
      if (flip_edges(rescue_only) == 0)
        return;
  }

  /// One pass over the edges; `rescue_only`: flip only to improve a triangle below the angle
  /// bound. Returns the number of flips.
  long flip_edges(bool rescue_only) {
    long flips = 0;
    if (!rescue_only)
      for (VertexIndex v : mesh_.vertices())
        valence_target_[v] = ideal_valence(v);
    for (EdgeIndex e : mesh_.edges()) {
      if (crease_[e])
        continue;
      const HalfedgeIndex h = mesh_.halfedge(e), o = mesh_.opposite(h);
      const VertexIndex a = mesh_.source(h), b = mesh_.target(h);
      const VertexIndex c = mesh_.target(mesh_.next(h)), d = mesh_.target(mesh_.next(o));
      if (c == d || mesh_.halfedge(c, d) != Mesh::null_halfedge())
        continue;
      const int degree_a = static_cast<int>(mesh_.degree(a));
      const int degree_b = static_cast<int>(mesh_.degree(b));
      if (degree_a <= 3 || degree_b <= 3)
        continue;
      const Vec3 pa = pos(a), pb = pos(b), pc = pos(c), pd = pos(d);
      // Faces (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c).
      const double old_min = std::min(min_angle(pa, pb, pc), min_angle(pb, pa, pd));
      const double new_min = std::min(min_angle(pc, pa, pd), min_angle(pd, pb, pc));
      const Vec3 n0 = face_normal(mesh_.face(h)), n1 = face_normal(mesh_.face(o));
      bool flip = false;
      if (old_min < in_.min_angle && new_min > old_min) {
        flip = true;  // rescue a bad triangle
      } else if (!rescue_only) {
        const int ta = valence_target_[a], tb = valence_target_[b];
        const int tc = valence_target_[c], td = valence_target_[d];
        const int degree_c = static_cast<int>(mesh_.degree(c));
        const int degree_d = static_cast<int>(mesh_.degree(d));
        auto square = [](int x) { return x * x; };
        const int before = square(degree_a - ta) + square(degree_b - tb) +
                           square(degree_c - tc) + square(degree_d - td);
        const int after = square(degree_a - 1 - ta) + square(degree_b - 1 - tb) +
                          square(degree_c + 1 - tc) + square(degree_d + 1 - td);
        flip = after < before && new_min >= std::min(in_.min_angle, old_min);
      }
      if (!flip)
        continue;
      // Both new faces must face the way both old ones did.
      const Vec3 m0 = unit_normal(pc, pa, pd), m1 = unit_normal(pd, pb, pc);
      if (m0.squaredNorm() == 0.0 || m1.squaredNorm() == 0.0 || m0.dot(n0) < cos_turn_ ||
          m0.dot(n1) < cos_turn_ || m1.dot(n0) < cos_turn_ || m1.dot(n1) < cos_turn_)
        continue;
      const int patch = fpatch_[mesh_.face(h)];
      CGAL::Euler::flip_edge(h, mesh_);
      fpatch_[mesh_.face(h)] = patch;
      fpatch_[mesh_.face(mesh_.opposite(h))] = patch;
      ++flips;
    }
    flips_ += flips;
    return flips;
  }

  /// Lawson's flips towards the Delaunay triangulation of each patch: an edge whose two
  /// opposite angles sum to more than π (plus a margin against flipping back and forth on
  /// cocircular points) is flipped, under the same normal guard as every flip.
  void delaunay_flips() {
    for (int pass = 0; pass < kDelaunayPasses; ++pass) {
      long flips = 0;
      for (EdgeIndex e : mesh_.edges()) {
        if (crease_[e])
          continue;
        const HalfedgeIndex h = mesh_.halfedge(e), o = mesh_.opposite(h);
        const VertexIndex a = mesh_.source(h), b = mesh_.target(h);
        const VertexIndex c = mesh_.target(mesh_.next(h)), d = mesh_.target(mesh_.next(o));
        if (c == d || mesh_.halfedge(c, d) != Mesh::null_halfedge() || mesh_.degree(a) <= 3 ||
            mesh_.degree(b) <= 3)
          continue;
        const Vec3 pa = pos(a), pb = pos(b), pc = pos(c), pd = pos(d);
        auto angle = [](const Vec3& apex, const Vec3& p, const Vec3& q) {
          const Vec3 u = p - apex, w = q - apex;
          return std::atan2(u.cross(w).norm(), u.dot(w));
        };
        if (angle(pc, pa, pb) + angle(pd, pa, pb) <= std::numbers::pi + kDelaunayMargin)
          continue;
        const Vec3 n0 = face_normal(mesh_.face(h)), n1 = face_normal(mesh_.face(o));
        const Vec3 m0 = unit_normal(pc, pa, pd), m1 = unit_normal(pd, pb, pc);
        if (m0.squaredNorm() == 0.0 || m1.squaredNorm() == 0.0 || m0.dot(n0) < cos_turn_ ||
            m0.dot(n1) < cos_turn_ || m1.dot(n0) < cos_turn_ || m1.dot(n1) < cos_turn_)
          continue;
        const int patch = fpatch_[mesh_.face(h)];
        CGAL::Euler::flip_edge(h, mesh_);
        fpatch_[mesh_.face(h)] = patch;
        fpatch_[mesh_.face(mesh_.opposite(h))] = patch;
        ++flips;
      }
      flips_ += flips;
      if (flips == 0)
        return;
    }
  }

  // ---- relaxation ------------------------------------------------------------------------

  /// Moves v to x if no face around it gets worse than the guards allow.
  bool try_move(VertexIndex v, const Vec3& x) {
    double old_min = std::numeric_limits<double>::infinity();
    for (FaceIndex f : CGAL::faces_around_target(mesh_.halfedge(v), mesh_))
      old_min = std::min(old_min, face_min_angle(f));
    for (HalfedgeIndex g : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_)) {
      const FaceIndex f = mesh_.face(g);
      const Vec3 a = pos(mesh_.source(g)), c = pos(mesh_.target(mesh_.next(g)));
      if (!acceptable(a, x, c, face_normal(f), old_min))
        return false;
    }
    set_position(v, x);
    ++moves_;
    return true;
  }

  void relax() {
    for (VertexIndex v : mesh_.vertices()) {
      if (kind_[v] == kCorner)
        continue;
      const Vec3 p = pos(v);
      if (kind_[v] == kChain) {
        // Slide along the straight crease between its two crease neighbours so that the two
        // crease edges have the same length relative to their target sizes.
        VertexIndex ends[2];
        int found = 0;
        for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_))
          if (crease_[mesh_.edge(h)] && found < 2)
            ends[found++] = mesh_.source(h);
        if (found != 2)
          throw InternalError("graded remeshing: a crease vertex without two crease edges");
        const Vec3 a = pos(ends[0]), b = pos(ends[1]);
        const double ha = target(ends[0], v), hb = target(ends[1], v);
        const Vec3 x = on_crease(a + (b - a) * (ha / (ha + hb)));
        if ((x - p).squaredNorm() > 0.0)
          try_move(v, x);
        continue;
      }
      // Free vertex: the centroid of the face centroids weighted by area/h³ (each face then
      // pulls in proportion to its size relative to its target, so a graded mesh is a fixed
      // point), moved in the tangent plane and put back onto the patch.
      Vec3 centroid = Vec3::Zero(), normal = Vec3::Zero();
      double weight = 0.0;
      for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_)) {
        const VertexIndex u = mesh_.source(h), w = mesh_.target(mesh_.next(h));
        const Vec3 a = pos(u), c = pos(w);
        const Vec3 cross = (p - a).cross(c - a);
        const double area = 0.5 * cross.norm();
        const double hf = (size_[u] + size_[v] + size_[w]) / 3.0;
        const double wf = area / (hf * hf * hf);
        centroid += wf * (a + p + c) / 3.0;
        weight += wf;
        normal += cross;
      }
      if (!(weight > 0.0) || normal.squaredNorm() == 0.0)
        continue;
      normal.normalize();
      centroid /= weight;
      Vec3 x = p + (centroid - p) - normal * (centroid - p).dot(normal);
      x = surfaces_[static_cast<std::size_t>(vpatch_[v])].project(x);
      if ((x - p).squaredNorm() > 0.0)
        try_move(v, x);
    }
  }

  // ---- rescue of the triangles below the angle bound ---------------------------------------

  /// Smallest angle of the faces around v with v at x; −1 if a face would degenerate or turn
  /// by more than the normal bound.
  double star_quality(VertexIndex v, const Vec3& x) const {
    double smallest = std::numeric_limits<double>::infinity();
    for (HalfedgeIndex g : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_)) {
      const Vec3 a = pos(mesh_.source(g)), c = pos(mesh_.target(mesh_.next(g)));
      const Vec3 n = unit_normal(a, x, c);
      if (n.squaredNorm() == 0.0 || n.dot(face_normal(mesh_.face(g))) < cos_turn_)
        return -1.0;
      smallest = std::min(smallest, min_angle(a, x, c));
    }
    return smallest;
  }

  /// Moves v to the position of the largest smallest angle among candidates: along its
  /// straight crease for a crease vertex, a compass search in the tangent plane (put back onto
  /// the patch) for a free one. Returns whether it moved.
  bool optimise_vertex(VertexIndex v) {
    if (kind_[v] == kCorner)
      return false;
    const Vec3 p = pos(v);
    double best = star_quality(v, p);
    Vec3 best_x = p;
    if (kind_[v] == kChain) {
      VertexIndex ends[2];
      int found = 0;
      for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_))
        if (crease_[mesh_.edge(h)] && found < 2)
          ends[found++] = mesh_.source(h);
      const Vec3 a = pos(ends[0]), b = pos(ends[1]);
      for (int k = 1; k < kRescueSamples; ++k) {
        const Vec3 x = on_crease(a + (b - a) * (static_cast<double>(k) / kRescueSamples));
        if (const double q = star_quality(v, x); q > best) {
          best = q;
          best_x = x;
        }
      }
    } else {
      Vec3 normal = Vec3::Zero();
      double edge_sum = 0.0;
      int edges = 0;
      for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh_.halfedge(v), mesh_)) {
        normal += (p - pos(mesh_.source(h))).cross(pos(mesh_.target(mesh_.next(h))) - pos(mesh_.source(h)));
        edge_sum += length(h);
        ++edges;
      }
      if (normal.squaredNorm() == 0.0)
        return false;
      normal.normalize();
      const Vec3 u = normal.unitOrthogonal(), w = normal.cross(u);
      const PatchSurface& surface = surfaces_[static_cast<std::size_t>(vpatch_[v])];
      for (double step = 0.25 * edge_sum / edges; step > 1e-3 * edge_sum / edges; step *= 0.5) {
        bool improved = true;
        while (improved) {
          improved = false;
          for (const Vec3& d : {u, Vec3(-u), w, Vec3(-w)}) {
            const Vec3 x = surface.project(best_x + step * d);
            if (const double q = star_quality(v, x); q > best) {
              best = q;
              best_x = x;
              improved = true;
            }
          }
        }
      }
    }
    if (best_x == p)
      return false;
    set_position(v, best_x);
    ++moves_;
    return true;
  }

  /// Faces whose smallest angle is below the bound: collapse their shortest edge where that
  /// makes the faces around better (allowing edges up to length_ratio·h), move their
  /// corners to the best position, flip where a flip helps.
  void rescue(double length_ratio = kRescueLengthRatio) {
    for (int pass = 0; pass < kRescuePasses; ++pass) {
      std::vector<FaceIndex> bad;
      for (FaceIndex f : mesh_.faces())
        if (face_min_angle(f) < in_.min_angle)
          bad.push_back(f);
      if (bad.empty())
        return;
      for (FaceIndex f : bad) {
        if (mesh_.is_removed(f) || face_min_angle(f) >= in_.min_angle)
          continue;
        HalfedgeIndex shortest = mesh_.halfedge(f);
        for (HalfedgeIndex h : CGAL::halfedges_around_face(mesh_.halfedge(f), mesh_))
          if (length(h) < length(shortest))
            shortest = h;
        double old_min = std::numeric_limits<double>::infinity();
        for (const HalfedgeIndex h : {shortest, mesh_.opposite(shortest)})
          for (FaceIndex g : CGAL::faces_around_target(mesh_.opposite(h), mesh_))
            old_min = std::min(old_min, face_min_angle(g));
        const double forward = collapse_quality(shortest, length_ratio);
        const double backward = collapse_quality(mesh_.opposite(shortest), length_ratio);
        if (std::max(forward, backward) > old_min) {
          collapse(forward >= backward ? shortest : mesh_.opposite(shortest));
          continue;
        }
        std::vector<VertexIndex> corners;
        for (VertexIndex v : CGAL::vertices_around_face(mesh_.halfedge(f), mesh_))
          corners.push_back(v);
        for (VertexIndex v : corners)
          optimise_vertex(v);
      }
      mesh_.collect_garbage();
      flip_until_settled(kFlipPasses, true);
    }
  }

  // ---- output ----------------------------------------------------------------------------

  GradedRemeshOutput output() {
    mesh_.collect_garbage();
    GradedRemeshOutput out;
    std::vector<int> index(mesh_.num_vertices(), -1);
    out.vertices.resize(static_cast<Eigen::Index>(mesh_.number_of_vertices()), 3);
    int next = 0;
    for (VertexIndex v : mesh_.vertices()) {
      out.vertices.row(next) = pos(v).transpose();
      index[static_cast<std::size_t>(v.idx())] = next++;
    }
    out.faces.resize(static_cast<Eigen::Index>(mesh_.number_of_faces()), 3);
    out.face_patch.resize(static_cast<Eigen::Index>(mesh_.number_of_faces()));
    Eigen::Index f = 0;
    for (FaceIndex fi : mesh_.faces()) {
      int k = 0;
      for (VertexIndex v : CGAL::vertices_around_face(mesh_.halfedge(fi), mesh_)) {
        if (k == 3)
          throw InternalError("graded remeshing produced a face that is not a triangle");
        out.faces(f, k++) = index[static_cast<std::size_t>(v.idx())];
      }
      out.face_patch(f) = fpatch_[fi];
      ++f;
    }
    out.splits = splits_;
    out.collapses = collapses_;
    out.flips = flips_;
    out.moves = moves_;
    return out;
  }

  const GradedRemeshInput& in_;
  Mesh mesh_;
  Mesh::Property_map<VertexIndex, unsigned char> kind_;
  Mesh::Property_map<VertexIndex, int> vpatch_;
  Mesh::Property_map<VertexIndex, double> size_;
  Mesh::Property_map<VertexIndex, Vec3> sized_at_;  // where size_ was evaluated
  Mesh::Property_map<VertexIndex, int> valence_target_;
  Mesh::Property_map<EdgeIndex, bool> crease_;
  Mesh::Property_map<FaceIndex, int> fpatch_;
  std::vector<PatchSurface> surfaces_;
  double cos_turn_ = 0.0;
  long splits_ = 0, collapses_ = 0, flips_ = 0, moves_ = 0;
  /// The input's crease edges, where curved creases let crease vertices leave their lines.
  std::vector<Segment> crease_segments_;
  std::unique_ptr<SegmentTree> crease_tree_;
};

}  // namespace

GradedRemeshOutput cgal_graded_remesh(const GradedRemeshInput& input) {
  return Remesher(input).run();
}

}  // namespace bemshape::geometry::detail
