#pragma once
// Pairs of skins that share a mid-surface point (docs/theory.md, "Wall thickness on the
// surface", near rims of curved walls).
//
// The mid-surface search (analysis/wall_thickness.hpp) takes every face f of the surface to
// the point p_f = x_f − τ_f n_f where the across-wall component of s vanishes. Both skins of
// a wall reach that set: s·n is odd across the wall for n and −n alike. The face g of the
// opposite skin (n_g·n_f < −kOppositeCosine) whose p_g is nearest p_f is the skin f faces
// across the wall, and the wall between them is their separation along the bisector m of
// the two normals:
//
//   t_f = (x_f − x_g)·m,   m = (n_f − n_g)/|n_f − n_g|                [model units]
//
// The solution chooses the pair (which skin is across the wall: no ray is cast, so a
// point near a corner or a junction has no partner rather than a wrong one); the pair gives
// the number. This reading is exact on curved walls, where twice the depth 2τ_f is off by
// about ±t²H/2 (H the mean curvature: ±7 % on the skins of a 30/24 mm tube, −13 % on the
// inside of a 3 mm sheet bent about a radius of 4), and on tapers, whose skins are not
// parallel, so that near the end face the zeros of s·n_f and s·n_g part (the last row of
// faces of a 2–6 mm taper have τ_f + τ_g = 0.87 t).

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

/// The opposite skin's normal makes an angle above 162° with the face's own (a skin
/// faceted as coarsely as 18° per facet still finds its partner; the bisector's reading is
/// then at most 1.2 % short of the separation of exactly opposite faces).
inline constexpr double kOppositeCosine = 0.95;

/// A pair is kept when the separation lies between this fraction and its inverse of the
/// sum of the two depths τ_f + τ_g (0.87 of the separation at a taper's thick end).
inline constexpr double kDepthAgreement = 0.5;

using FaceMask = Eigen::Array<bool, Eigen::Dynamic, 1>;

struct MidSurfacePairs {
  Eigen::VectorXd thickness;  ///< #F t_f [model units]; NaN where no partner was found
  Eigen::VectorXi partner;    ///< #F the face g across the wall; −1 where none
};

/// t_f and g for the faces `wanted` marks (see above); none where a face has no mid-surface
/// point (NaN depth), no face of the opposite skin has one within ½τ_f + 2·(the face's edge
/// length) of p_f, or the nearest one's separation disagrees with the depths
/// (kDepthAgreement). Partners are taken among the faces `across` marks only: those whose
/// search crossed their own wall (an end face's search runs along the wall and stops where
/// the wall turns, next to the mid-surface points of the skins there: a 3 mm L-bracket's
/// outer corner would pair with the top of its 40 mm leg).
///   mid_point: #F×3 p_f, NaN rows where none was found; depth: #F τ_f.
MidSurfacePairs mid_surface_pairs(const geometry::SurfaceMesh& mesh,
                                  const Eigen::MatrixX3d& mid_point, const Eigen::VectorXd& depth,
                                  const FaceMask& wanted, const FaceMask& across);

}  // namespace bemshape::analysis
