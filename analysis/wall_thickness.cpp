#include "analysis/wall_thickness.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/mid_surface_pairs.hpp"
#include "analysis/separation_at_scale.hpp"
#include "bem/evaluate/laplace_treecode.hpp"
#include "bem/evaluate/surface_gradient.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/quadrature/panel.hpp"
#include "core/cancellation.hpp"
#include "features/feature_tensor.hpp"
#include "features/wall_thickness.hpp"
#include "geometry/face_adjacency.hpp"

namespace bemshape::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Evaluations per face at most: Newton converges in one or two from the flat-wall first
/// step on flat and curved walls, the growth steps of a search along a wall stop at
/// kAlongWallDepthRatio, and a bracket shrinks superlinearly.
constexpr int kMaxSteps = 16;
/// The first step is at least this fraction of h0 deep.
constexpr double kMinDepthRatio = 1e-3;
/// A search that must go deeper than this times the wall read at its current point runs
/// along the wall: features::along_wall classifies 2τ0 > kAlongWallRatio·h_mid, i.e.
/// τ0 > 0.75·h_mid, as such; twice that leaves a margin for h_mid changing on the way.
constexpr double kAlongWallDepthRatio = features::kAlongWallRatio;
/// The across-wall direction of the field (the eigenvector of λ3, where λ2 is below this
/// fraction of λ3, so that it is defined: not at the axis of a rod or the centre of a ball)...
constexpr double kDistinctEigenvalueRatio = 0.5;
/// ... more than 60° from the search direction: the search runs along the wall.
constexpr double kAlongWallCosine = 0.5;
/// The treecode's order and acceptance (bem/evaluate/laplace_treecode.hpp). θ = 0.5 admits
/// clusters at twice their radius, where θ = 0.3 admits them at three times: the mid-surface
/// of a wall meshed with elements as long as the wall is thick lies within a panel or two of
/// the surface, where most of the cost is the exact integrals of the panels the criterion
/// does not admit (the l-bracket's wall stage 2.5 → 1.5 s against θ = 0.3, the readings
/// unchanged to 1e−5); those are taken within 1e−6 (bem/evaluate/near_panel_integrals.hpp).
/// At θ = 0.5 the truncation error goes as θ^{p+1}, 16 times per two orders (4.4e−5 of ∇s at
/// p = 10 on the ball, docs/benchmarks.md, "Interior evaluation at many points"): p = 7
/// leaves an estimated 4e−4 of ∇s with 120 Taylor terms instead of p = 10's 286. The readings
/// of the bench's parts move by at most 1e−4 of the wall and the search takes 0.6 of the time
/// (plate_holes 2.4–2.7 → 1.5 s). p = 6 (1.2 s) moves the worst face half a wall from the
/// step of 2 to 4 from 3.96 to 4.03 % off, past its test's 4 %; p = 4 moves plate_holes'
/// median by 0.13 % (docs/benchmarks.md, "What was tried and did not pay").
constexpr int kTreecodeOrder = 7;
constexpr double kTreecodeTheta = 0.5;
/// A partner reading a rim (rim indicator from features::kRimFull on) must read at least
/// this fraction of the pair's separation as its own h_mid (see the pairing below).
constexpr double kPartnerReadingRatio = 0.5;
/// Panels per leaf of the treecode's cluster tree: smaller leaves than the evaluation of
/// `features` (16), so that fewer panels near a point are integrated exactly.
constexpr Eigen::Index kLeafSize = 8;

struct FaceResult {
  bool found = false;
  double depth = kNaN, mid_thickness = kNaN, rim_indicator = kNaN;
  /// |n·e3| at p0 (e3 the across-wall eigenvector), NaN where λ2 is not below
  /// kDistinctEigenvalueRatio·λ3 (the axis of a rod, the centre of a ball).
  double alignment = kNaN;
  Eigen::Vector3d point = Eigen::Vector3d::Constant(kNaN);
  int evaluations = 0;
  /// The search stopped because it ran along the wall (no zero found: an end face, a hole's
  /// wall), not because it left the solid or went past the part.
  bool ran_along = false;
};

class MidSurfaceSearch {
 public:
  MidSurfaceSearch(const bem::LaplaceTreecode& treecode, double reach,
                   const features::FeatureParameters& parameters)
      : treecode_(treecode), reach_(reach), parameters_(parameters) {}

  /// Safeguarded Newton on g(τ) = s(x − τn)·n, whose derivative g'(τ) = −nᵀ(∇s)n comes with
  /// every evaluation of ∇s (see the top of wall_thickness.hpp).
  FaceResult operator()(const Eigen::Vector3d& x, const Eigen::Vector3d& n, double g0,
                        double slope0, bem::LaplaceTreecode::Workspace& workspace,
                        bem::TreecodeCounts& counts) const {
    FaceResult result;
    if (!(std::abs(g0) > 0.0)) return result;
    const bool positive = g0 > 0.0;
    // First step: the middle of a flat wall (g falls linearly from g0 with slope q·n).
    double tau = slope0 * g0 > 0.0 ? g0 / slope0 : 0.5 * parameters_.h0;
    tau = std::clamp(tau, kMinDepthRatio * parameters_.h0, reach_);
    double lo = 0.0, g_lo = g0, hi = kNaN, g_hi = kNaN;
    // The previous evaluation's depth and h_mid: the slope of h_mid along −n.
    double tau_before = kNaN, h_mid_before = kNaN;
    for (int step = 0; step < kMaxSteps; ++step) {
      ++result.evaluations;
      const bem::LaplaceTreecode::Value v = treecode_.evaluate(x - tau * n, workspace, counts);
      if (!(v.winding > 0.5)) return result;  // left the solid: no mid-surface along −n
      const double g = v.s.dot(n.transpose());
      const double slope = -n.dot(v.gradient * n);
      if ((g > 0.0) == positive) {
        lo = tau;
        g_lo = g;
      } else {
        hi = tau;
        g_hi = g;
      }
      // Newton's step where g falls from g0 towards its zero (g0·g' < 0), else none.
      double next = g0 * slope < 0.0 ? tau - g / slope : kNaN;
      const auto tensor = features::feature_tensor<3>(v.gradient);
      const double h_mid =
          features::mid_surface_thickness(tensor.eigenvalues, parameters_.h0, parameters_.a);
      if (std::isfinite(next) && std::abs(next - tau) <= kNewtonAcceptance * tau) {
        // The readings moved from τ to τ0 = next: s along its gradient, h_mid along the line
        // through this and the previous evaluation (where there is one).
        const double shift = next - tau;
        result.depth = next;
        result.point = x - next * n;
        result.mid_thickness = h_mid;
        if (std::isfinite(tau_before) && std::isfinite(h_mid_before) && tau != tau_before)
          result.mid_thickness += (h_mid - h_mid_before) / (tau - tau_before) * shift;
        result.rim_indicator = (v.s.transpose() - shift * (v.gradient * n)).norm() / std::abs(g0);
        if (tensor.eigenvalues(1) < kDistinctEigenvalueRatio * tensor.eigenvalues(2))
          result.alignment = std::abs(tensor.eigenvectors.col(2).dot(n));
        result.found = true;
        return result;
      }
      tau_before = tau;
      h_mid_before = h_mid;
      if (std::isfinite(hi)) {
        // Bracketed: Newton inside the bracket, else regula falsi.
        if (!(next > lo && next < hi)) next = lo - g_lo * (hi - lo) / (g_hi - g_lo);
        if (hi - lo <= kDepthTolerance * lo) next = std::abs(g_lo) <= std::abs(g_hi) ? lo : hi;
      } else {
        // Not bracketed: Newton's step where it goes forward (from a convex g it approaches
        // the zero from this side), else by kDepthGrowth; at most kMaxNewtonGrowth deeper.
        if (!(next > tau)) next = kDepthGrowth * tau;
        next = std::min(next, kMaxNewtonGrowth * tau);
        // The search runs along a wall (from a rim face, a hole's wall, the end of a rib), not
        // across it: the wall the field reads here lies across another direction than n, or
        // its mid-surface would be far deeper than that wall is thick.
        const Eigen::Vector3d& lambda = tensor.eigenvalues;
        const bool across_other = lambda(1) < kDistinctEigenvalueRatio * lambda(2) &&
                                  std::abs(tensor.eigenvectors.col(2).dot(n)) < kAlongWallCosine;
        if (across_other || next > kAlongWallDepthRatio * h_mid) {
          result.ran_along = true;
          return result;
        }
        if (tau >= reach_) return result;
        next = std::min(next, reach_);
      }
      tau = next;
    }
    return result;
  }

 private:
  const bem::LaplaceTreecode& treecode_;
  double reach_;
  const features::FeatureParameters& parameters_;
};

/// Gives every face without a value (NaN) the area-weighted mean of its edge neighbours'
/// values, sweep by sweep until none is left (or nothing changes: a shell with no value).
void fill_from_neighbours(const geometry::SurfaceMesh& mesh, Eigen::VectorXd& values) {
  const Eigen::Index nf = mesh.num_faces();
  const std::vector<std::vector<int>> neighbours = geometry::edge_neighbours(mesh.faces());
  for (bool changed = true; changed;) {
    changed = false;
    Eigen::VectorXd next = values;
    for (Eigen::Index f = 0; f < nf; ++f) {
      if (std::isfinite(values(f))) continue;
      double sum = 0.0, weight = 0.0;
      for (int g : neighbours[static_cast<std::size_t>(f)])
        if (std::isfinite(values(g))) {
          sum += mesh.face_areas()(g) * values(g);
          weight += mesh.face_areas()(g);
        }
      if (weight > 0.0) {
        next(f) = sum / weight;
        changed = true;
      }
    }
    values = std::move(next);
  }
}

}  // namespace

WallThickness wall_thickness(const geometry::SurfaceMesh& mesh,
                             const bem::BoundarySolution& solution,
                             const features::FeatureParameters& parameters,
                             const ProgressCallback& progress, StageTimes* times) {
  StageTimes own;
  StageTimes& stages = times ? *times : own;
  const auto search_start = StageTimes::Clock::now();
  const Eigen::Index nf = mesh.num_faces();
  const std::vector<bem::Panel> panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, kLeafSize);
  const bem::LaplaceTreecode treecode(panels, tree, solution.q, solution.phi,
                                      {kTreecodeOrder, kTreecodeTheta, true});
  const Eigen::MatrixX3d vertex_s = bem::reconstruct_vertex_values(mesh, solution.phi);
  const MidSurfaceSearch search(treecode, mesh.bounding_box().diagonal(), parameters);

  WallThickness result;
  result.thickness.setConstant(nf, kNaN);
  result.mid_point.setConstant(nf, 3, kNaN);
  result.depth.setConstant(nf, kNaN);
  result.mid_thickness.setConstant(nf, kNaN);
  result.rim_indicator.setConstant(nf, kNaN);
  result.alignment.setConstant(nf, kNaN);
  std::vector<char> ran_along(static_cast<std::size_t>(nf), 0);
  std::atomic<Eigen::Index> done{0};
  std::uint64_t evaluations = 0;
#pragma omp parallel reduction(+ : evaluations)
  {
    bem::LaplaceTreecode::Workspace workspace = treecode.workspace();
    bem::TreecodeCounts counts;
    // Faces in cluster-tree order: consecutive searches of a thread lie close together and
    // visit the same clusters, whose moments then stay in the cache.
    const auto& order = tree.permutation();
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index t = 0; t < nf; ++t) {
      if (cancellation_requested()) continue;
      const Eigen::Index f = order[std::size_t(t)];
      const Eigen::Vector3d x = mesh.face_centroids().row(f).transpose();
      const Eigen::Vector3d n = mesh.face_normals().row(f).transpose();
      Eigen::Vector3d s0 = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) s0 += vertex_s.row(mesh.faces()(f, k)).transpose() / 3.0;
      const double slope0 = solution.q.row(f).dot(n.transpose());
      const FaceResult face = search(x, n, s0.dot(n), slope0, workspace, counts);
      evaluations += static_cast<std::uint64_t>(face.evaluations);
      ran_along[static_cast<std::size_t>(f)] = face.ran_along;
      if (face.found) {
        result.depth(f) = face.depth;
        result.mid_point.row(f) = face.point.transpose();
        result.mid_thickness(f) = face.mid_thickness;
        result.rim_indicator(f) = face.rim_indicator;
        result.alignment(f) = face.alignment;
      }
      const Eigen::Index count = ++done;
      if (progress && count % 256 == 0) {
#pragma omp critical(bemshape_progress)
        report_progress(progress, "wall thickness", double(count) / double(nf));
      }
    }
  }
  throw_if_cancelled();
  result.evaluations = evaluations;
  const auto pairing_start = StageTimes::Clock::now();
  stages.add("mid-surface search",
             std::chrono::duration<double>(pairing_start - search_start).count());
  // The skins' separation where two of them share a mid-surface point: the rim reading,
  // and the wall's reading at a junction.
  FaceMask found(nf), across(nf);
  for (Eigen::Index f = 0; f < nf; ++f) {
    found(f) = std::isfinite(result.depth(f));
    across(f) = std::isfinite(result.depth(f)) &&
                !features::along_wall(result.mid_thickness(f), 2.0 * result.depth(f)) &&
                !features::oblique(result.alignment(f));
  }
  MidSurfacePairs pairs = mid_surface_pairs(mesh, result.mid_point, result.depth, found, across);
  // A partner whose own field reads a rim and a wall under half the pair's separation is no
  // skin across that wall: a noisy face on a convex edge, tilted towards the neighbouring
  // wall, whose search found the zero of s·n in the edge's wedge before leaving the solid
  // (on plate_holes' σ = 3 % copy: rim indicator 1.9, h_mid 2.9 against a separation of
  // 8–10 from the rounded edge across the plate; the skins of a tray's floor beside its
  // pocket, rim indicators 0.1–0.2, keep their pairs at h_mid = 0.49 of the separation).
  for (Eigen::Index f = 0; f < nf; ++f) {
    const int g = pairs.partner(f);
    if (g >= 0 && result.rim_indicator(g) >= features::kRimFull &&
        !(result.mid_thickness(g) >= kPartnerReadingRatio * pairs.thickness(f))) {
      pairs.thickness(f) = kNaN;
      pairs.partner(f) = -1;
    }
  }
  result.pair_thickness = separation_at_scale(mesh, pairs.thickness,
                                              kSeparationScaleRatio * parameters.h0);
  result.partner = std::move(pairs.partner);
  result.paired_faces = (result.partner.array() >= 0).count();
  for (Eigen::Index f = 0; f < nf; ++f)
    if (std::isfinite(result.depth(f)))
      result.thickness(f) =
          features::wall_thickness(result.mid_thickness(f), 2.0 * result.depth(f),
                                   result.rim_indicator(f), result.pair_thickness(f),
                                   result.alignment(f));
  result.filled_faces = (!result.thickness.array().isFinite()).count();
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (std::isfinite(result.thickness(f))) continue;
    Fallback kind =
        ran_along[static_cast<std::size_t>(f)] ? Fallback::along_wall : Fallback::no_mid_surface;
    if (std::isfinite(result.depth(f))) {
      if (features::along_wall(result.mid_thickness(f), 2.0 * result.depth(f)))
        kind = Fallback::along_wall;
      else if (features::oblique(result.alignment(f)))
        kind = Fallback::oblique;
      else
        kind = Fallback::rim_without_pair;
    }
    FallbackFaces& counted = result.fallback[static_cast<std::size_t>(kind)];
    const Eigen::Vector3d c = mesh.face_centroids().row(f).transpose();
    counted.box.min = counted.faces == 0 ? c : counted.box.min.cwiseMin(c);
    counted.box.max = counted.faces == 0 ? c : counted.box.max.cwiseMax(c);
    ++counted.faces;
    counted.area += mesh.face_areas()(f);
  }
  fill_from_neighbours(mesh, result.thickness);
  // A shell where no face has a value of its own: h_mid where there is one, else not
  // measurable.
  for (Eigen::Index f = 0; f < nf; ++f)
    if (!std::isfinite(result.thickness(f)))
      result.thickness(f) = std::isfinite(result.mid_thickness(f))
                                ? result.mid_thickness(f)
                                : features::kMaxThicknessFactor * parameters.h0;
  stages.add("pairing",
             std::chrono::duration<double>(StageTimes::Clock::now() - pairing_start).count());
  report_progress(progress, "wall thickness", 1.0);
  return result;
}

const char* to_string(Fallback kind) {
  switch (kind) {
    case Fallback::no_mid_surface: return "no_mid_surface";
    case Fallback::along_wall: return "along_wall";
    case Fallback::oblique: return "oblique";
    case Fallback::rim_without_pair: return "rim_without_pair";
  }
  return "unknown";
}

Eigen::VectorXd vertex_mean(const geometry::SurfaceMesh& mesh, const Eigen::VectorXd& face_values) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.num_vertices());
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      sum(mesh.faces()(f, k)) += mesh.face_areas()(f) * face_values(f);
      weight(mesh.faces()(f, k)) += mesh.face_areas()(f);
    }
  return (sum.array() / weight.array().max(std::numeric_limits<double>::min())).matrix();
}

}  // namespace bemshape::analysis
