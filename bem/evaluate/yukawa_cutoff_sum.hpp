#pragma once
// The exterior (Yukawa) representation formula at one point, summed only over the panels
// the kernel still reaches:
//
//   s_i(x) = −∫_Γ Gκ(x−y) q_out,i dA_y + ∫_Γ ∂Gκ/∂n_y φ_i dA_y,   Gκ(r) = e^{−κr}/(4πr),
//
// and ∂s_i/∂x_j, with n outward, q_out = q − n_i/ã the exterior normal derivative and P0
// densities (#F×3, face order). Gκ decays exponentially, so panels whose gap
// |x − centroid| − radius exceeds g* = −ln(negligible)/κ contribute less than `negligible`
// of an unattenuated panel and are skipped — the dropping rule and default threshold of the
// exterior operators (YukawaAttenuation::negligible = 1e−10, g* ≈ 23/κ;
// bem/solve/yukawa_near_field.hpp). The cluster tree finds the remaining panels: a
// cluster whose box is farther than g* + the largest panel radius from x holds none. The
// cost per point is the number of panels within about g* of it — O(1) whatever #F, and 0
// for points farther than g* from the surface.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/quadrature/panel.hpp"

namespace bemshape::bem {

class YukawaCutoffSum {
 public:
  /// `panels` in face order, `tree` over them (both must outlive this object); q_out and φ
  /// #F×3 in face order; κ > 0 [1/model units]; 0 < negligible < 1.
  YukawaCutoffSum(const std::vector<Panel>& panels, const ClusterTree& tree, double kappa,
                  const Eigen::Ref<const Eigen::MatrixX3d>& q_out,
                  const Eigen::Ref<const Eigen::MatrixX3d>& phi, double negligible);

  struct Value {
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();   ///< s_i(x) [model units]
    Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();  ///< (i, j) = ∂s_i/∂x_j
  };

  /// s and ∇s at x; `stack` is scratch space; adds the panel integrals done to `panel_integrals`.
  Value evaluate(const Eigen::Vector3d& x, std::vector<int>& stack,
                 std::uint64_t& panel_integrals) const;

  /// g* = −ln(negligible)/κ [model units].
  double cutoff() const { return cutoff_; }

 private:
  const std::vector<Panel>* panels_;
  const ClusterTree* tree_;
  double kappa_;
  double cutoff_;
  double reach_;                  ///< g* + largest panel radius
  Eigen::MatrixX3d q_out_, phi_;  ///< in face order
};

}  // namespace bemshape::bem
