#pragma once
// The wall thickness on the surface of the solid: for every solver face, the thickness of
// the wall the face belongs to, read at the wall's mid-surface (docs/theory.md, "Wall
// thickness"; the formulas are features/wall_thickness.hpp).
//
// The search, per face f with centroid x and outward normal n, on g(τ) = s(x − τn)·n:
//   - g(0) from the reconstructed vertex values of s (bem/evaluate/surface_gradient.hpp) and
//     the first step τ1 = g(0)/(q·n), the depth of the middle of a flat wall;
//   - Newton's step τ − g/g' (g' = −nᵀ(∇s)n from the same evaluation) goes forward until g
//     changes sign (at most kMaxNewtonGrowth times deeper per step; by kDepthGrowth where
//     Newton does not go forward), the point leaves the solid (winding number below ½) or τ
//     passes the diagonal of the part's bounding box;
//   - Newton's step ends the search once it is shorter than kNewtonAcceptance·τ; a
//     bracketed zero where Newton would leave the bracket shrinks by regula falsi until it is
//     narrower than kDepthTolerance·τ; the end is the mid-surface point p0 = x − τ0·n;
//   - s and ∇s at p0 (bem/evaluate/laplace_treecode.hpp, the interior representation
//     formula) give h_mid, and the rim indicator |s(p0)| / |g(0)|;
//   - the face of the opposite skin whose mid-surface point is nearest p0 gives the skins'
//     separation (analysis/mid_surface_pairs.hpp): the rim reading (else twice the depth),
//     and the reading where h_mid is a junction's (features/wall_thickness.hpp).
// Faces whose search leaves the solid or finds no sign change (a few at corners where three
// walls meet), and faces whose search ran along their wall instead of across it (the rim
// faces of a plate, the wall of a hole, the end of a rib or a tube:
// features::wall_thickness gives NaN) take the area-weighted mean of their edge neighbours'
// values, sweep by sweep until every face has one: a rim reads the wall it bounds. Their
// number is reported.
//
//   thickness:       #F wall thickness per solver face [model units]
//   mid_point:       #F×3 p0 [model units]; NaN rows where none was found
//   depth:           #F τ0 [model units]; NaN where none was found
//   mid_thickness:   #F h_mid [model units]; NaN where none was found
//   rim_indicator:   #F [1]; NaN where none was found
//   alignment:       #F |n·e3| at p0 [1] (e3 the field's across-wall direction); NaN where
//                    none was found or the direction is not defined (a rod's axis)
//   pair_thickness:  #F [model units]; NaN where no pair was found

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "analysis/stage_times.hpp"
#include "bem/solve/boundary_solution.hpp"
#include "core/progress.hpp"
#include "features/feature_parameters.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::analysis {

/// The search's relative resolution of τ0: 10⁻³ of the depth moves the twice-depth reading
/// by 0.1 % and h_mid (a smooth function of the position across the wall) by less.
inline constexpr double kDepthTolerance = 1e-3;
/// A Newton step shorter than this fraction of the depth is the last: its end is τ0 (Newton's
/// error is of the order of the step squared over the wall), and the readings are moved there
/// from the point just evaluated (s along ∇s, h_mid along the line through the last two
/// evaluations). Many faces need one evaluation fewer than at 10⁻³ (plate_holes 1.99 → 1.76
/// per face). At 2 % the readings on curved walls move by up to 1.2e−3 of the wall for 5 %
/// fewer evaluations; at 5 % the tube's by up to 0.7 % (its median by 0.16 %), for 15 %
/// fewer (docs/benchmarks.md, "What was tried and did not pay").
inline constexpr double kNewtonAcceptance = 0.01;
/// Growth of τ between steps while no sign change is found and Newton's step does not go
/// forward (g rising, or g' of the wrong sign).
inline constexpr double kDepthGrowth = 1.6;
/// At most this factor deeper per step before the zero is bracketed.
inline constexpr double kMaxNewtonGrowth = 4.0;

/// Why a face has no reading of its own and took its neighbours' (features/wall_thickness.hpp).
enum class Fallback {
  no_mid_surface,    ///< the search left the solid or found no sign change of s·n
  along_wall,        ///< the search ran along the wall: stopped as such before a zero (the
                     ///< field's wall across another direction, or deeper than
                     ///< kAlongWallRatio of it), or 2τ0 > kAlongWallRatio·h_mid
  oblique,           ///< the search crossed its wall obliquely (|n·e3| < kMinAlignment)
  rim_without_pair,  ///< near a rim (rim indicator above kRimFrom) and no opposite skin
                     ///< paired: a skin more than arccos(kOppositeCosine) from opposite
};
inline constexpr int kFallbackKinds = 4;

/// "no_mid_surface", "along_wall", "oblique", "rim_without_pair".
const char* to_string(Fallback kind);

/// The faces that fell back for one reason: how many, their area [model units²] and where
/// (the bounding box of their centroids; zero where there are none).
struct FallbackFaces {
  Eigen::Index faces = 0;
  double area = 0.0;
  geometry::BoundingBox box;
};

/// The share of the surface's area above which the faces that fell back for a reason other
/// than along_wall (end faces and hole walls always do) are reported with a warning: there
/// the reading is the neighbours', not the face's own (docs/usage.md, "Faces that fell back").
inline constexpr double kFallbackWarningShare = 0.05;

struct WallThickness {
  Eigen::VectorXd thickness;
  Eigen::MatrixX3d mid_point;
  Eigen::VectorXd depth;
  Eigen::VectorXd mid_thickness;
  Eigen::VectorXd rim_indicator;
  Eigen::VectorXd alignment;
  /// The separation of the two skins sharing the mid-surface point
  /// (analysis/mid_surface_pairs.hpp); NaN where the opposite skin has no face there.
  Eigen::VectorXd pair_thickness;
  /// The face across the wall whose skin shares the mid-surface point; −1 where none.
  Eigen::VectorXi partner;
  Eigen::Index paired_faces = 0;
  /// Faces given their neighbours' thickness (no mid-surface point, or searched along the wall).
  Eigen::Index filled_faces = 0;
  /// The faces counted in filled_faces, by reason (indexed by Fallback).
  std::array<FallbackFaces, kFallbackKinds> fallback{};
  /// Points where s was evaluated (the search's cost).
  std::uint64_t evaluations = 0;
};

/// The wall thickness of every face of `solver_mesh` from its boundary solution. Parallel over
/// faces; polls cancellation; reports progress as "wall thickness". With `times`, adds the
/// stages "mid-surface search" (the treecode and the search) and "pairing" (the skins across
/// the wall, the readings and the neighbours' fill).
WallThickness wall_thickness(const geometry::SurfaceMesh& solver_mesh,
                             const bem::BoundarySolution& solution,
                             const features::FeatureParameters& parameters,
                             const ProgressCallback& progress = {}, StageTimes* times = nullptr);

/// Per-vertex values of a per-face field: the area-weighted mean over each vertex's faces.
Eigen::VectorXd vertex_mean(const geometry::SurfaceMesh& mesh, const Eigen::VectorXd& face_values);

}  // namespace bemshape::analysis
