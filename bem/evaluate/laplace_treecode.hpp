#pragma once
// The interior (Laplace) representation formula at many points by a Cartesian treecode,
// O(log #F) per point instead of a sum over every panel:
//
//   s_i(x)  = ∫_Γ G0(x−y) q_i dA_y − ∫_Γ ∂G0/∂n_y φ_i dA_y,   G0(r) = 1/(4πr),
//   w(x)    = −∫_Γ ∂G0/∂n_y dA_y             (winding number: 1 inside, 0 outside),
//   ∂s_i/∂x_j by differentiating in x,
//
// with n outward and P0 densities q, φ (#F×3, bem/solve/boundary_solution.hpp).
//
// Far field. For a cluster of panels with centre c and radius ρ (every panel corner within
// ρ of c), y = c + d and R = x − c, the Taylor series of 1/|R − d| in d
// (bem/evaluate/inverse_distance_taylor.hpp) gives, truncated at order p,
//
//   4π s_i(x) ≈ Σ_{|β|≤p} C_β^{(i)} b_β(R),   4π ∂_k s_i(x) ≈ Σ_{|β|≤p} C_β^{(i)} (β_k+1)
//   b_{β+e_k}(R), C_β^{(i)} = ∫ [ q_i (−d)^β − φ_i n·∇_d (−d)^β ] dA
//             = ∫ [ q_i (−d)^β + φ_i Σ_j n_j β_j (−d)^{β−e_j} ] dA,
//
// and the winding number with the moments C_β^{(w)} = ∫ Σ_j n_j β_j (−d)^{β−e_j} dA. The
// moments of the 3 directions and of the winding number are stored together,
// 4·(p+1)(p+2)(p+3)/6 numbers per cluster. On each flat panel the integrands are polynomials
// of degree ≤ p, so a triangle rule of degree p (bem/quadrature/triangle_quadrature.hpp) computes the
// leaf moments exactly; parents get theirs by shifting their children's
// ((−d − t)^β = Σ_{γ≤β} binom(β, γ) (−d)^γ (−t)^{β−γ}, t = c_child − c_parent), so the
// only approximation is the truncation of the Taylor series.
//
// Evaluation walks the cluster tree (bem/hmatrix/cluster_tree.hpp) from the root: a
// cluster with ρ < θ·|R| (the multipole acceptance criterion) is evaluated by its expansion,
// otherwise its children are visited; the panels of a leaf that fails the criterion are
// integrated exactly (bem/quadrature/panel_integrals.hpp, accurate on and near the panel), which keeps
// the accuracy of the direct sum near the surface. The truncation error of an accepted
// cluster is bounded by its absolute moment times (ρ/|R|)^{p+1}/(|R| − ρ); clusters well
// inside the criterion use the lowest order p' ≤ p with (ρ/|R|)^{p'+1} ≤ θ^{p+1}, the bound
// of a cluster at the edge of the criterion, so far clusters are cheaper and no less
// accurate. Measured errors and costs: docs/benchmarks.md, "Interior evaluation at many
// points".

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/evaluate/inverse_distance_taylor.hpp"
#include "bem/quadrature/panel.hpp"

namespace bemshape::bem {

struct LaplaceTreecodeParameters {
  /// Expansion order p (0 ≤ p ≤ kMaxOrder). The default pair is for_tolerance(1e−6).
  int order = 10;
  /// Acceptance parameter θ (0 < θ < 1): a cluster's expansion is used when ρ < θ·|x − c|.
  double theta = 0.3;
  /// The panels of the leaves the criterion does not admit are integrated within
  /// kNearPanelAccuracy (1e−6, bem/evaluate/near_panel_integrals.hpp) instead of the 1e−8 of
  /// integrate_panel: for pairs (p, θ) whose own error is well above 1e−6 (θ = 0.5), about
  /// half the cost of an evaluation near the surface.
  bool near_field_at_treecode_accuracy = false;

  /// Largest order accepted: order 14 already reaches 5e−10 (docs/benchmarks.md), and the
  /// leaf moments of order 16 need a 9 × 9-point rule on every panel.
  static constexpr int kMaxOrder = 16;

  /// The cheapest measured (p, θ) whose error relative to the direct sum (max over points
  /// of the error in s, ∇s and the winding number, each relative to the largest value of
  /// that quantity) stayed below `tolerance` on a ball and a hollow box
  /// (docs/benchmarks.md); (kMaxOrder, 0.25), not measured, below 5e−10.
  static LaplaceTreecodeParameters for_tolerance(double tolerance);
};

/// Work done by evaluations (summed over points).
struct TreecodeCounts {
  std::uint64_t expansions = 0;       ///< cluster expansions evaluated
  std::uint64_t panel_integrals = 0;  ///< exact panel integrals (leaves failing the criterion)
};

class LaplaceTreecode {
 public:
  /// Builds the moments. `panels` in mesh face order (bem::make_panels), `tree` over them,
  /// q and φ #F×3 in face order; `panels` and `tree` must outlive the treecode. Throws
  /// InputError for parameters outside their ranges.
  LaplaceTreecode(const std::vector<Panel>& panels, const ClusterTree& tree,
                  const Eigen::Ref<const Eigen::MatrixX3d>& q,
                  const Eigen::Ref<const Eigen::MatrixX3d>& phi,
                  LaplaceTreecodeParameters parameters = {});

  struct Value {
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();   ///< s_i(x) [model units]
    Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();  ///< (i, j) = ∂s_i/∂x_j
    double winding = 0.0;                                ///< w(x)
  };

  /// Scratch space of one thread.
  struct Workspace {
    std::vector<double> taylor;
    std::vector<int> stack;
  };
  Workspace workspace() const;

  /// s, ∇s and w at x; adds the work done to `counts`.
  Value evaluate(const Eigen::Vector3d& x, Workspace& workspace, TreecodeCounts& counts) const;
  /// s and w at x only (Value::gradient stays zero): the Taylor terms of one order less and
  /// no gradient integrals, about half the work of evaluate().
  Value evaluate_values(const Eigen::Vector3d& x, Workspace& workspace,
                        TreecodeCounts& counts) const;

  const LaplaceTreecodeParameters& parameters() const { return parameters_; }
  /// Memory held by the moments [bytes].
  std::uint64_t moment_bytes() const { return moments_.size() * sizeof(double); }

 private:
  template <bool kGradient>
  Value sum(const Eigen::Vector3d& x, Workspace& workspace, TreecodeCounts& counts) const;

  /// Values per multi-index: s_1, s_2, s_3 and the winding number.
  static constexpr int kSets = 4;

  const std::vector<Panel>* panels_;
  const ClusterTree* tree_;
  LaplaceTreecodeParameters parameters_;
  MultiIndexTable table_;     ///< degree p + 1 (the gradient needs one more)
  int coefficients_;          ///< count(p)
  Eigen::MatrixX3d q_, phi_;  ///< in tree order
  std::vector<Eigen::Vector3d> centre_;
  std::vector<double> radius_;
  /// Per cluster, coefficients_ × kSets, multi-index major.
  std::vector<double> moments_;
  /// β + e_i and β_i + 1 for the gradient, per multi-index of degree ≤ p.
  struct Raise {
    std::array<int, 3> index;
    std::array<double, 3> factor;
  };
  std::vector<Raise> raise_;
  /// ln θ^{p+1}: the per-cluster order is the least p' with (p'+1)·ln(ρ/|R|) ≤ this.
  double log_error_bound_;
};

}  // namespace bemshape::bem
