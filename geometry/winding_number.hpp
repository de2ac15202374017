#pragma once
// Generalized winding number of a closed triangle surface around a point:
//
//   w(p) = (1/4π) Σ_f Ω_f(p),
//
// Ω_f the signed solid angle of triangle f seen from p (Van Oosterom & Strackee, IEEE Trans.
// Biomed. Eng. 30(2), 1983: tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|),
// a, b, c the corners relative to p). For a closed, outward-oriented surface w = 1 inside,
// 0 outside (−1 inside an inward-oriented one); it is exact up to rounding for points away
// from the surface and needs no ray casting, so it also decides how shells are nested.

#include <Eigen/Core>

namespace bemshape::geometry {

/// w(p) for the triangles `faces` (#F×3 indices into `vertices`, #V×3 [model units]).
double winding_number(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                      const Eigen::Vector3d& point);

}  // namespace bemshape::geometry
