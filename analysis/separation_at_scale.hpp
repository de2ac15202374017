#pragma once
// The skins' separation at the scale h0 (docs/theory.md, "The scale h0"). The separation of
// the two skins that share a mid-surface point (analysis/mid_surface_pairs.hpp) is a
// distance between two faces: it carries every detail of the surface, a scan's noise or a
// pit far narrower than h0, straight into the reading wherever it is taken (at rims and
// junctions, features/wall_thickness.hpp). Averaged over the faces of the same skin within
// a disc of radius r = kSeparationScaleRatio·h0,
//
//   t̄_f = Σ_g A_g t_g / Σ_g A_g  over the paired faces g with |c_g − c_f| ≤ r and
//                                  n_g·n_f ≥ kSameSkinCosine              [model units]
//
// (A the face areas, c the centroids, n the unit normals), it reads a wall as wide as h0
// and wider (a rib, a tab, a groove's floor: the disc lies on the feature) and not a detail
// much smaller (a pit of h0/4: the disc is mostly the skin around it). The noise of a skin
// at the vertex scale falls as the square root of the faces in the disc.

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

/// r = this·h0: a disc of diameter h0, the smallest feature that counts.
inline constexpr double kSeparationScaleRatio = 0.5;
/// Faces of the same skin: normals within 30° (a skin's facets and a scan's noise tilt the
/// normals by a few degrees; a wall's side or a groove's wall is at 90°).
inline constexpr double kSameSkinCosine = 0.866;

/// t̄ (see above) for every face with a finite `separation` (#F, NaN where a face has no
/// pair; those stay NaN); `radius` > 0 [model units].
Eigen::VectorXd separation_at_scale(const geometry::SurfaceMesh& mesh,
                                    const Eigen::VectorXd& separation, double radius);

}  // namespace bemshape::analysis
