#pragma once
// Shape features on the surface of the solid, from the interior side, and their transfer
// from the refined solver mesh back to the user's (original) mesh.
//
// On the solver mesh (bem/evaluate/surface_gradient.hpp gives ∇s per face and per vertex):
//   per vertex: s = reconstructed vertex value, ∇s = vertex gradient (the area-weighted mean
//               of the adjacent faces' gradients)
//   per face:   s = φ (P0 value), ∇s = mean of the three corner vertex gradients
// and features::compute_features<3> with χ = 1 (the interior limit).
// Why faces use the averaged gradient rather than their own: h_p takes the LARGEST
// eigenvalue of the feature tensor, so the O(h) face-to-face noise of the P0 normal
// derivative q biases it upwards (thinner walls) wherever the tensor is near-isotropic.
// Measured on the ball R = 0.5, h0 = 0.3, a = 0.2 at the default element size (1280 faces):
// the face's own gradient gives h_p up to 3.7 % below the closed form, the averaged one
// 1.0 %; on a flat plate both agree to 0.1 %.
//
// Transfer to the original mesh (both meshes describe the same surface: the solver mesh's
// vertices lie on the original triangles):
//   original vertex → closest point on the solver mesh, barycentric interpolation of the
//                     solver mesh's vertex values;
//   original face   → area-weighted mean of the solver faces whose centroids are closest to
//                     that original face; a face that no solver centroid falls on (a sliver
//                     narrower than the solver's elements) takes the solver face closest to
//                     its own centroid.
// Orientation vectors are renormalised after averaging (zero stays zero).
//
// Columns of every `values` matrix (kFeatureColumns):
//   0 f_h [1], 1 h_f [model units], 2 h_p [model units], 3–5 n_f (unit vector),
//   6 wall [model units]: the wall thickness read at the mid-surface
//     (analysis/wall_thickness.hpp); NaN unless the caller computed it (measure_thickness
//     does for its `wall` measure).

#include <Eigen/Core>

#include "bem/solve/boundary_solution.hpp"
#include "features/feature_parameters.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

inline constexpr int kFeatureColumns = 7;
inline constexpr int kColumnFh = 0, kColumnHf = 1, kColumnHp = 2, kColumnNf = 3, kColumnWall = 6;

struct SurfaceFeatures {
  Eigen::MatrixXd vertex;  ///< #V×kFeatureColumns
  Eigen::MatrixXd face;    ///< #F×kFeatureColumns
};

/// Features on the solver mesh from its boundary solution.
SurfaceFeatures surface_features(const geometry::SurfaceMesh& solver_mesh,
                                 const bem::BoundarySolution& solution,
                                 const features::FeatureParameters& parameters);

/// The solver mesh's features carried over to `target` (the original mesh).
SurfaceFeatures transfer_features(const geometry::SurfaceMesh& solver_mesh,
                                  const SurfaceFeatures& solver_features,
                                  const geometry::SurfaceMesh& target);

}  // namespace bemshape::analysis
