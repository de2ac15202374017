#include "bem/evaluate/potential_evaluation.hpp"

#include <atomic>
#include <cstdint>
#include <optional>

#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/evaluate/laplace_treecode.hpp"
#include "bem/evaluate/yukawa_cutoff_sum.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/evaluate/surface_gradient.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "core/cancellation.hpp"
#include "geometry/closest_point.hpp"

namespace bemshape::bem {
namespace {

/// Interior targets closer to the surface than this many diameters of the nearest panel get
/// their gradient by interpolation (see evaluate_potential). Measured on the ball: the
/// representation formula's gradient with P0 densities is accurate to the discretisation
/// error from about 0.7 panel diameters inward and wrong by up to a factor of 3 at 1% of h0.
constexpr double kNearSurfaceDiameters = 1.0;

/// The panel sums of the representation formulas: direct over every panel, or by the tree.
struct PanelSums {
  const std::vector<Panel>& panels;
  const BoundarySolution& solution;
  Eigen::MatrixX3d q_out;  ///< q − n/ã
  const PotentialEvaluationOptions& options;
  std::optional<ClusterTree> tree;
  std::optional<LaplaceTreecode> laplace;
  std::optional<YukawaCutoffSum> yukawa;

  PanelSums(const geometry::SurfaceMesh& mesh, const std::vector<Panel>& panels_,
            const BoundarySolution& solution_, const PotentialEvaluationOptions& options_)
      : panels(panels_),
        solution(solution_),
        q_out(solution_.q - mesh.face_normals() / solution_.parameters.a_tilde),
        options(options_) {
    if (options.direct || panels.empty()) return;
    tree.emplace(panels, options.leaf_size);
    laplace.emplace(panels, *tree, solution.q, solution.phi, options.treecode);
    yukawa.emplace(panels, *tree, solution.parameters.kappa, q_out, solution.phi,
                   options.yukawa_negligible);
  }
};

/// The representation formulas at every point (no near-surface treatment).
PotentialField represent(const PanelSums& sums, const Eigen::Ref<const Eigen::MatrixX3d>& points,
                         const ProgressCallback& progress) {
  const LaplaceKernel laplace{};
  const YukawaKernel yukawa{sums.solution.parameters.kappa};
  const BoundarySolution& solution = sums.solution;
  const std::vector<Panel>& panels = sums.panels;
  const Eigen::Index np = points.rows(), nf = static_cast<Eigen::Index>(panels.size());

  PotentialField field;
  field.s.resize(np, 3);
  field.gradient.resize(np, 9);
  field.winding.resize(np);
  field.inside.assign(static_cast<size_t>(np), 0);
  std::atomic<Eigen::Index> done{0};
  std::atomic<std::uint64_t> laplace_panels{0}, expansions{0}, yukawa_panels{0};
#pragma omp parallel
  {
    std::optional<LaplaceTreecode::Workspace> workspace;
    if (sums.laplace) workspace = sums.laplace->workspace();
    std::vector<int> stack;
    TreecodeCounts counts;
    std::uint64_t yukawa_count = 0;
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index p = 0; p < np; ++p) {
      // A cancelled run skips the remaining points (an exception cannot leave the loop).
      if (cancellation_requested()) continue;
      const Eigen::Vector3d x = points.row(p).transpose();
      double winding = 0.0;
      Eigen::RowVector3d s_in = Eigen::RowVector3d::Zero(), s_out = Eigen::RowVector3d::Zero();
      Eigen::Matrix3d g_in = Eigen::Matrix3d::Zero(), g_out = Eigen::Matrix3d::Zero();
      // The interior (Laplace) sums first: they give the winding number too, and the exterior
      // (Yukawa) sums are needed only where it says the point is outside.
      if (sums.laplace) {
        const LaplaceTreecode::Value v = sums.laplace->evaluate(x, *workspace, counts);
        winding = v.winding;
        s_in = v.s;
        g_in = v.gradient;
      } else {
        for (Eigen::Index k = 0; k < nf; ++k) {
          const PanelIntegrals l = integrate_panel(laplace, panels[static_cast<size_t>(k)], x, true);
          winding -= l.double_layer;
          const Eigen::RowVector3d q = solution.q.row(k), phi = solution.phi.row(k);
          s_in += l.single_layer * q - l.double_layer * phi;
          // g(i, j) = ∂s_i/∂x_j: outer products of the densities with the kernel gradients.
          g_in += q.transpose() * l.single_layer_gradient.transpose() -
                  phi.transpose() * l.double_layer_gradient.transpose();
        }
        counts.panel_integrals += std::uint64_t(nf);
      }
      if (!(winding > 0.5)) {
        if (sums.yukawa) {
          const YukawaCutoffSum::Value v = sums.yukawa->evaluate(x, stack, yukawa_count);
          s_out = v.s;
          g_out = v.gradient;
        } else {
          for (Eigen::Index k = 0; k < nf; ++k) {
            const PanelIntegrals y = integrate_panel(yukawa, panels[static_cast<size_t>(k)], x, true);
            const Eigen::RowVector3d phi = solution.phi.row(k), qo = sums.q_out.row(k);
            s_out += -y.single_layer * qo + y.double_layer * phi;
            g_out += -qo.transpose() * y.single_layer_gradient.transpose() +
                     phi.transpose() * y.double_layer_gradient.transpose();
          }
          yukawa_count += std::uint64_t(nf);
        }
      }
      const bool inside = winding > 0.5;
      field.winding(p) = winding;
      field.inside[static_cast<size_t>(p)] = inside ? 1 : 0;
      field.s.row(p) = inside ? s_in : s_out;
      const Eigen::Matrix3d& g = inside ? g_in : g_out;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) field.gradient(p, 3 * i + j) = g(i, j);
      const Eigen::Index count = ++done;
      if (progress && count % 256 == 0) {
#pragma omp critical(bemshape_progress)
        report_progress(progress, "evaluate", double(count) / double(np));
      }
    }
    laplace_panels += counts.panel_integrals;
    expansions += counts.expansions;
    yukawa_panels += yukawa_count;
  }
  throw_if_cancelled();
  field.cost = {laplace_panels.load(), expansions.load(), yukawa_panels.load(),
                static_cast<std::uint64_t>(np), sums.laplace ? sums.laplace->moment_bytes() : 0};
  return field;
}

}  // namespace

PotentialField evaluate_potential(const geometry::SurfaceMesh& mesh,
                                  const BoundarySolution& solution,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                  const ProgressCallback& progress,
                                  const PotentialEvaluationOptions& options) {
  const std::vector<Panel> panels = make_panels(mesh);
  const PanelSums sums(mesh, panels, solution, options);
  PotentialField field = represent(sums, points, progress);

  // Near-surface interior targets: ∇s along the segment from the closest surface point y
  // inward is smooth (s is harmonic), so interpolate it quadratically in the distance t from
  // three samples: the surface gradient at y (t = 0, from φ and q) and the representation
  // formula at t = δ and 2δ, δ = kNearSurfaceDiameters × the nearest panel's diameter.
  const geometry::ClosestPointQuery closest(mesh);
  const geometry::ClosestPoints nearest = closest.closest_points(points);
  std::vector<Eigen::Index> near;
  std::vector<double> spacing;
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    if (!field.inside[static_cast<size_t>(p)]) continue;
    const double delta =
        kNearSurfaceDiameters * panels[static_cast<size_t>(nearest.faces(p))].diameter;
    if (nearest.distances(p) < delta) {
      near.push_back(p);
      spacing.push_back(delta);
    }
  }
  if (!near.empty()) {
    const SurfaceGradient surface = interior_surface_gradient(mesh, solution);
    const auto m = static_cast<Eigen::Index>(near.size());
    Eigen::MatrixX3d samples(2 * m, 3);
    Eigen::MatrixX3d direction(m, 3);
    for (Eigen::Index i = 0; i < m; ++i) {
      const Eigen::Index p = near[static_cast<size_t>(i)];
      const Eigen::Index f = nearest.faces(p);
      const Eigen::Vector3d y = nearest.points.row(p).transpose();
      Eigen::Vector3d u = points.row(p).transpose() - y;
      // Targets (almost) on the surface take the inward normal of their face.
      if (u.norm() < 1e-3 * spacing[static_cast<size_t>(i)])
        u = -mesh.face_normals().row(f).transpose();
      u.normalize();
      direction.row(i) = u.transpose();
      samples.row(2 * i) = (y + spacing[static_cast<size_t>(i)] * u).transpose();
      samples.row(2 * i + 1) = (y + 2.0 * spacing[static_cast<size_t>(i)] * u).transpose();
    }
    const PotentialField far = represent(sums, samples, {});
    field.cost.laplace_panel_integrals += far.cost.laplace_panel_integrals;
    field.cost.laplace_expansions += far.cost.laplace_expansions;
    field.cost.yukawa_panel_integrals += far.cost.yukawa_panel_integrals;
    field.cost.points += far.cost.points;
    for (Eigen::Index i = 0; i < m; ++i) {
      const Eigen::Index p = near[static_cast<size_t>(i)];
      const Eigen::Index f = nearest.faces(p);
      Eigen::RowVectorXd g0 = Eigen::RowVectorXd::Zero(9);
      for (int k = 0; k < 3; ++k)
        g0 += nearest.barycentric(p, k) * surface.vertex_gradient.row(mesh.faces()(f, k));
      const double delta = spacing[static_cast<size_t>(i)], t = nearest.distances(p);
      const bool first_inside = far.inside[static_cast<size_t>(2 * i)] != 0;
      const bool second_inside = far.inside[static_cast<size_t>(2 * i + 1)] != 0;
      if (first_inside && second_inside) {
        // Lagrange weights of the nodes 0, δ, 2δ at t.
        const double l0 = (t - delta) * (t - 2 * delta) / (2 * delta * delta);
        const double l1 = t * (t - 2 * delta) / (-delta * delta);
        const double l2 = t * (t - delta) / (2 * delta * delta);
        field.gradient.row(p) =
            l0 * g0 + l1 * far.gradient.row(2 * i) + l2 * far.gradient.row(2 * i + 1);
      } else if (first_inside) {
        // A wall thinner than 2δ: linear between the surface and the first sample.
        field.gradient.row(p) = (1.0 - t / delta) * g0 + (t / delta) * far.gradient.row(2 * i);
      } else {
        field.gradient.row(p) = g0;
      }
    }
  }
  report_progress(progress, "evaluate", 1.0);
  return field;
}

}  // namespace bemshape::bem
