#pragma once
// The gradient of s on the surface, from the interior side, out of the boundary data:
//
//   ∇s_i = ∇_Γ φ_i + q_i·n          (tangential part from φ, normal part from q)
//
// φ is piecewise constant (P0) on the faces; ∇_Γ φ needs a continuous reconstruction. Vertex
// values come from a least-squares fit of an affine function to the centroid values of the
// faces around the vertex (exact for affine φ, second order for smooth φ on any star, also
// across sharp edges because the fit is in 3-D); each face then takes the gradient of the
// linear interpolant of its three vertex values, which is tangential to the face.
//
//   face_gradient:   #F×9, ∂s_i/∂x_j at column 3i + j [dimensionless]
//   vertex_gradient: #V×9, area-weighted mean of the adjacent faces' gradients
//   vertex_values:   #V×3, reconstructed s at the vertices [model units]

#include <Eigen/Core>

#include "bem/solve/boundary_solution.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::bem {

struct SurfaceGradient {
  Eigen::MatrixXd face_gradient;
  Eigen::MatrixXd vertex_gradient;
  Eigen::MatrixX3d vertex_values;
};

/// #V×3 vertex values of a P0 field (#F×3) by local affine least squares in the tangent
/// plane of each vertex star (see above).
Eigen::MatrixX3d reconstruct_vertex_values(const geometry::SurfaceMesh& mesh,
                                           const Eigen::MatrixX3d& face_values);

/// Interior-side gradient tensor of s per face and per vertex.
SurfaceGradient interior_surface_gradient(const geometry::SurfaceMesh& mesh,
                                          const BoundarySolution& solution);

}  // namespace bemshape::bem
