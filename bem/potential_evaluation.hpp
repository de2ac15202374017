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
// bem/surface_gradient.hpp) and the representation formula one and two panel diameters
// from y. s itself is taken from the representation formula everywhere (it is accurate up
// to the surface). Exterior targets keep the representation formula's gradient: features
// are not evaluated outside the solid.
//
//   points:   #P×3 [model units]
//   s:        #P×3 [model units]
//   gradient: #P×9, ∂s_i/∂x_j at column 3i + j [dimensionless]
//   winding:  #P, ≈1 inside, ≈0 outside, ½ on the surface

#include <vector>

#include <Eigen/Core>

#include "bem/boundary_solution.hpp"
#include "core/progress.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::bem {

struct PotentialField {
  Eigen::MatrixX3d s;
  Eigen::MatrixXd gradient;
  Eigen::VectorXd winding;
  std::vector<char> inside;  ///< winding > ½
};

/// Evaluates s and ∇s at every point, in parallel over points. Cost: #P × #F panel
/// integrals.
PotentialField evaluate_potential(const geometry::SurfaceMesh& mesh,
                                  const BoundarySolution& solution,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                  const ProgressCallback& progress = {});

}  // namespace bemshape::bem
