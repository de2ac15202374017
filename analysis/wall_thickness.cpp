#include "analysis/wall_thickness.hpp"

#include "analysis/mid_surface_pairs.hpp"
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/mid_surface_pairs.hpp"
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
/// Regula falsi steps at most (the Illinois variant converges superlinearly: three or four
/// steps reach kDepthTolerance from the first bracket).
constexpr int kMaxRefinements = 12;
/// Accuracy of the interior sums relative to the largest value of s: the zero of g is found
/// to about this fraction of the wall, well below kDepthTolerance.
constexpr double kTreecodeTolerance = 1e-5;
/// Panels per leaf of the treecode's cluster tree (bem::PotentialEvaluationOptions's default).
constexpr Eigen::Index kLeafSize = 16;

struct FaceResult {
  bool found = false;
  double depth = kNaN, mid_thickness = kNaN, rim_indicator = kNaN;
  Eigen::Vector3d point = Eigen::Vector3d::Constant(kNaN);
  int evaluations = 0;
};

class MidSurfaceSearch {
 public:
  MidSurfaceSearch(const bem::LaplaceTreecode& treecode, double reach,
                   const features::FeatureParameters& parameters)
      : treecode_(treecode), reach_(reach), parameters_(parameters) {}

  FaceResult operator()(const Eigen::Vector3d& x, const Eigen::Vector3d& n, double g0,
                        double slope0, bem::LaplaceTreecode::Workspace& workspace,
                        bem::TreecodeCounts& counts) const {
    FaceResult result;
    if (!(std::abs(g0) > 0.0)) return result;
    auto across = [&](double tau, bool& inside) {
      ++result.evaluations;
      const bem::LaplaceTreecode::Value v =
          treecode_.evaluate_values(x - tau * n, workspace, counts);
      inside = v.winding > 0.5;
      return v.s.dot(n.transpose());
    };
    // First step: the middle of a flat wall (g falls linearly from g0 with slope q·n).
    double step = slope0 * g0 > 0.0 ? g0 / slope0 : 0.5 * parameters_.h0;
    step = std::max(step, 1e-3 * parameters_.h0);
    double lo = 0.0, g_lo = g0, hi = kNaN, g_hi = kNaN;
    for (double tau = step;; tau = std::min(tau * kDepthGrowth, reach_)) {
      bool inside = true;
      const double g = across(tau, inside);
      if (!inside) return result;
      if ((g > 0.0) != (g0 > 0.0)) {
        hi = tau;
        g_hi = g;
        break;
      }
      lo = tau;
      g_lo = g;
      if (tau >= reach_) return result;
    }
    // Illinois: after two steps on the same side, halve the other end's value.
    int side = 0;
    for (int k = 0; k < kMaxRefinements && hi - lo > kDepthTolerance * lo; ++k) {
      const double tau = lo - g_lo * (hi - lo) / (g_hi - g_lo);
      bool inside = true;
      const double g = across(tau, inside);
      if ((g > 0.0) == (g0 > 0.0)) {
        lo = tau;
        g_lo = g;
        if (side == -1) g_hi *= 0.5;
        side = -1;
      } else {
        hi = tau;
        g_hi = g;
        if (side == 1) g_lo *= 0.5;
        side = 1;
      }
    }
    result.depth = std::abs(g_lo) <= std::abs(g_hi) ? lo : hi;
    result.point = x - result.depth * n;
    ++result.evaluations;
    const bem::LaplaceTreecode::Value v = treecode_.evaluate(result.point, workspace, counts);
    const auto tensor = features::feature_tensor<3>(v.gradient);
    result.mid_thickness =
        features::mid_surface_thickness(tensor.eigenvalues, parameters_.h0, parameters_.a);
    result.rim_indicator = v.s.norm() / std::abs(g0);
    result.found = true;
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
                             const ProgressCallback& progress) {
  const Eigen::Index nf = mesh.num_faces();
  const std::vector<bem::Panel> panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, kLeafSize);
  const bem::LaplaceTreecode treecode(
      panels, tree, solution.q, solution.phi,
      bem::LaplaceTreecodeParameters::for_tolerance(kTreecodeTolerance));
  const Eigen::MatrixX3d vertex_s = bem::reconstruct_vertex_values(mesh, solution.phi);
  const MidSurfaceSearch search(treecode, mesh.bounding_box().diagonal(), parameters);

  WallThickness result;
  result.thickness.setConstant(nf, kNaN);
  result.mid_point.setConstant(nf, 3, kNaN);
  result.depth.setConstant(nf, kNaN);
  result.mid_thickness.setConstant(nf, kNaN);
  result.rim_indicator.setConstant(nf, kNaN);
  std::atomic<Eigen::Index> done{0};
  std::uint64_t evaluations = 0;
#pragma omp parallel reduction(+ : evaluations)
  {
    bem::LaplaceTreecode::Workspace workspace = treecode.workspace();
    bem::TreecodeCounts counts;
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index f = 0; f < nf; ++f) {
      if (cancellation_requested()) continue;
      const Eigen::Vector3d x = mesh.face_centroids().row(f).transpose();
      const Eigen::Vector3d n = mesh.face_normals().row(f).transpose();
      Eigen::Vector3d s0 = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) s0 += vertex_s.row(mesh.faces()(f, k)).transpose() / 3.0;
      const double slope0 = solution.q.row(f).dot(n.transpose());
      const FaceResult face = search(x, n, s0.dot(n), slope0, workspace, counts);
      evaluations += static_cast<std::uint64_t>(face.evaluations);
      if (face.found) {
        result.depth(f) = face.depth;
        result.mid_point.row(f) = face.point.transpose();
        result.mid_thickness(f) = face.mid_thickness;
        result.rim_indicator(f) = face.rim_indicator;
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
  // The skins' separation where two of them share a mid-surface point: the rim reading,
  // and the wall's reading at a junction.
  FaceMask found(nf), across(nf);
  for (Eigen::Index f = 0; f < nf; ++f) {
    found(f) = std::isfinite(result.depth(f));
    across(f) = std::isfinite(result.depth(f)) &&
                !features::along_wall(result.mid_thickness(f), 2.0 * result.depth(f));
  }
  MidSurfacePairs pairs = mid_surface_pairs(mesh, result.mid_point, result.depth, found, across);
  result.pair_thickness = std::move(pairs.thickness);
  result.partner = std::move(pairs.partner);
  result.paired_faces = (result.partner.array() >= 0).count();
  for (Eigen::Index f = 0; f < nf; ++f)
    if (std::isfinite(result.depth(f)))
      result.thickness(f) =
          features::wall_thickness(result.mid_thickness(f), 2.0 * result.depth(f),
                                   result.rim_indicator(f), result.pair_thickness(f));
  result.filled_faces = (!result.thickness.array().isFinite()).count();
  fill_from_neighbours(mesh, result.thickness);
  // A shell where no face has a value of its own: h_mid where there is one, else not
  // measurable.
  for (Eigen::Index f = 0; f < nf; ++f)
    if (!std::isfinite(result.thickness(f)))
      result.thickness(f) = std::isfinite(result.mid_thickness(f))
                                ? result.mid_thickness(f)
                                : features::kMaxThicknessFactor * parameters.h0;
  report_progress(progress, "wall thickness", 1.0);
  return result;
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
