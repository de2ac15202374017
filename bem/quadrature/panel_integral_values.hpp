#pragma once
// The result of integrating a kernel over one flat panel with unit density, for one target x:
// the entries V[x, T], K[x, T] of the single- and double-layer operators and, on request,
// their gradients with respect to the target. Conventions (n the panel's right-hand-rule
// normal, outward for bemshape meshes):
//
//   single_layer           = ∫_T G(|x − y|) dA_y                         [model units]
//   double_layer           = ∫_T ∂G/∂n_y dA_y,  ∂G/∂n_y = G'(r)(y − x)·n/r  [dimensionless]
//   single_layer_gradient  = ∇_x single_layer                             [dimensionless]
//   double_layer_gradient  = ∇_x double_layer                             [1/model units]
//
// For Laplace the double layer of a closed outward surface summed over its panels is −1
// inside, −½ on the surface (principal value) and 0 outside.

#include <Eigen/Core>

namespace bemshape::bem {

struct PanelIntegrals {
  double single_layer = 0.0;
  double double_layer = 0.0;
  /// Zero unless gradients were requested.
  Eigen::Vector3d single_layer_gradient = Eigen::Vector3d::Zero();
  Eigen::Vector3d double_layer_gradient = Eigen::Vector3d::Zero();
};

}  // namespace bemshape::bem
