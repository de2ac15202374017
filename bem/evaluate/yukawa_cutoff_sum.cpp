#include "bem/evaluate/yukawa_cutoff_sum.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "bem/quadrature/panel_integrals.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "core/errors.hpp"

namespace bemshape::bem {

YukawaCutoffSum::YukawaCutoffSum(const std::vector<Panel>& panels, const ClusterTree& tree,
                                 double kappa, const Eigen::Ref<const Eigen::MatrixX3d>& q_out,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& phi, double negligible)
    : panels_(&panels), tree_(&tree), kappa_(kappa), q_out_(q_out), phi_(phi) {
  if (!(negligible > 0.0 && negligible < 1.0))
    throw InternalError("YukawaCutoffSum: negligible = " + std::to_string(negligible) +
                        " must lie in (0, 1)");
  (void)YukawaKernel{kappa};  // validates κ
  cutoff_ = -std::log(negligible) / kappa;
  double max_radius = 0.0;
  for (const Panel& p : panels)
    max_radius = std::max(max_radius, p.radius);
  // A panel's centroid lies in its cluster's box, so |x − centroid| − radius ≤ g* needs the
  // box within g* + radius of x.
  reach_ = cutoff_ + max_radius;
}

YukawaCutoffSum::Value YukawaCutoffSum::evaluate(const Eigen::Vector3d& x, std::vector<int>& stack,
                                                 std::uint64_t& panel_integrals) const {
  const YukawaKernel yukawa{kappa_};
  const auto& perm = tree_->permutation();
  const BoundingBox point{x, x};
  Value v;
  tree_->for_each_leaf_near(point, reach_, stack, [&](const Cluster& leaf) {
    for (Eigen::Index t = leaf.begin; t < leaf.end; ++t) {
      const Eigen::Index f = perm[size_t(t)];
      const Panel& panel = (*panels_)[size_t(f)];
      if ((x - panel.centroid).norm() - panel.radius > cutoff_)
        continue;
      const PanelIntegrals y = integrate_panel(yukawa, panel, x, true);
      ++panel_integrals;
      const Eigen::RowVector3d phi = phi_.row(f), qo = q_out_.row(f);
      v.s += -y.single_layer * qo + y.double_layer * phi;
      v.gradient += -qo.transpose() * y.single_layer_gradient.transpose() +
                    phi.transpose() * y.double_layer_gradient.transpose();
    }
  });
  return v;
}

}  // namespace bemshape::bem
