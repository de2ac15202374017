#pragma once
// Face normals of a noisy surface at a chosen scale, with its sharp edges kept: the bilateral
// normal filter (Zheng, Fu, Au, Tai, "Bilateral normal filtering for mesh denoising", IEEE
// TVCG 2011). Each sweep replaces every face normal by
//
//   n_i ← normalize( Σ_j A_j · W_s(|c_i − c_j|) · W_r(|n_i − n_j|) · n_j ),
//   W_s(d) = exp(−d²/(2σ_s²)),   W_r(x) = exp(−x²/(2σ_r²)),
//
// over the faces j that share a vertex with i (i included), A_j the area and c_j the
// centroid of face j. The spatial weight averages over σ_s per sweep; k sweeps spread it over
// about σ_s·√k. The range weight keeps faces on the two sides of a sharp edge apart: at
// σ_r = 0.35 (normals 20° apart) a 90° edge (|n_i − n_j| = √2) gets the weight 3·10⁻⁴,
// while the random tilts of a scanned or coarsely exported surface (a median dihedral angle
// of 12° between neighbours for vertex noise of 3 % of a 4 mm wall on 0.9 mm facets) get
// 0.8–0.9 and average out.
//
// Only the normals are filtered; the surface is not moved. What uses them:
// surface_creases.hpp, whose dihedral angles at a scale tell a part's edges from its noise.

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

/// σ_r of the range weight: normals this far apart (|n_i − n_j|, 0.35 ≈ 20°) weigh e^{−1/2}.
inline constexpr double kBilateralRangeSigma = 0.35;
/// Sweeps at most, whatever the ratio of the scale to the faces' size.
inline constexpr int kMaxBilateralSweeps = 64;

/// #F×3 unit normals of `mesh` filtered at the spatial scale `scale` [model units] (> 0): as
/// many sweeps of σ_s = the mean edge length as make σ_s·√k reach `scale` (at least one, at
/// most kMaxBilateralSweeps). Faces of zero area keep their (zero) normal. Parallel.
Eigen::MatrixX3d bilateral_face_normals(const SurfaceMesh& mesh, double scale,
                                        double range_sigma = kBilateralRangeSigma);

}  // namespace bemshape::geometry
