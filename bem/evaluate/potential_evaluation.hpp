#pragma once
// s and ∇s at arbitrary points from the boundary data, by the representation formulas
// (n outward, φ = s_i|Γ, q = ∂_n s_i from inside, q_out = q − n_i/ã):
//
//   inside Ω:   s_i(x) =  ∫_Γ G0(x−y) q dA_y − ∫_Γ ∂G0/∂n_y φ dA_y
//   outside Ω:  s_i(x) = −∫_Γ Gκ(x−y) q_out dA_y + ∫_Γ ∂Gκ/∂n_y φ dA_y
//
// and their gradients in x. Whether x is inside is decided by the same integrals: the
// Laplace double layer of the unit density is −1 inside and 0 outside, so the winding
// number w(x) = −∫_Γ ∂G0/∂n_y dA_y needs no separate point-in-solid test.
//
// With piecewise-constant densities the gradient of the representation formula is wrong
// within about a panel diameter of the surface (the densities jump between panels). For
// interior targets that close, ∇s is interpolated quadratically along the segment from the
// closest surface point y inward, between the surface gradient at y (from φ and q,
// bem/evaluate/surface_gradient.hpp) and the representation formula one and two panel diameters
// from y. s itself is taken from the representation formula everywhere (it is accurate up
// to the surface). Exterior targets keep the representation formula's gradient: features
// are not evaluated outside the solid.
//
//   points:   #P×3 [model units]
//   s:        #P×3 [model units]
//   gradient: #P×9, ∂s_i/∂x_j at column 3i + j [dimensionless]
//   winding:  #P, ≈1 inside, ≈0 outside, ½ on the surface
//
// Cost. By default the interior sums are a treecode (bem/evaluate/laplace_treecode.hpp:
// expansions of well-separated panel clusters, exact panel integrals for the near ones) and
// the exterior sums skip the panels the Yukawa kernel no longer reaches
// (bem/evaluate/yukawa_cutoff_sum.hpp): O(log #F) per point instead of #F. The direct
// sums over every panel remain as the reference (PotentialEvaluationOptions::direct).

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bem/solve/boundary_solution.hpp"
#include "bem/evaluate/laplace_treecode.hpp"
#include "core/progress.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::bem {

struct PotentialEvaluationOptions {
  /// Sum every panel for every point (#P × #F panel integrals): the reference the fast sums
  /// are measured against.
  bool direct = false;
  /// Expansion order and acceptance parameter of the interior treecode. The default keeps
  /// s, ∇s and the winding number within 1e−6 of the direct sums (relative to the largest
  /// value of each), the default GMRES tolerance of the fast path: the evaluation adds no
  /// error above the solve's.
  LaplaceTreecodeParameters treecode = LaplaceTreecodeParameters::for_tolerance(1e-6);
  /// Panels per leaf of the cluster tree both fast sums walk.
  Eigen::Index leaf_size = kDefaultTreeLeafSize;
  /// Measured on the sphere of 20,480 faces at 10⁴ grid points (docs/benchmarks.md): the
  /// CPU time is the same within noise for 8, 16 and 32; 16 holds less memory than 8 and
  /// does fewer exact panel integrals than 32.
  static constexpr Eigen::Index kDefaultTreeLeafSize = 16;
  /// Exterior panels attenuated below this (e^{−κ·gap}) are skipped. The default is the
  /// threshold of the assembled exterior operators (YukawaAttenuation::negligible = 1e−10).
  double yukawa_negligible = 1e-10;
};

/// Work done by one evaluation, including the near-surface samples.
struct EvaluationCost {
  std::uint64_t laplace_panel_integrals = 0;  ///< exact interior panel integrals
  std::uint64_t laplace_expansions = 0;       ///< treecode cluster expansions
  std::uint64_t yukawa_panel_integrals = 0;   ///< exact exterior panel integrals
  std::uint64_t points = 0;  ///< points the representation formulas were evaluated at
  std::uint64_t moment_bytes = 0;  ///< memory of the treecode's moments [bytes]
};

struct PotentialField {
  Eigen::MatrixX3d s;
  Eigen::MatrixXd gradient;
  Eigen::VectorXd winding;
  std::vector<char> inside;  ///< winding > ½
  EvaluationCost cost;
};

/// Evaluates s and ∇s at every point, in parallel over points.
PotentialField evaluate_potential(const geometry::SurfaceMesh& mesh,
                                  const BoundarySolution& solution,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                  const ProgressCallback& progress = {},
                                  const PotentialEvaluationOptions& options = {});

}  // namespace bemshape::bem
