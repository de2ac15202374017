#pragma once
// The thickness of the wall a surface point belongs to, read at the wall's mid-surface
// (docs/theory.md, "Wall thickness"). Pure functions of values the caller has evaluated; the
// search for the mid-surface is analysis/wall_thickness.hpp.
//
// The mid-surface of a wall is where the across-wall component of s changes sign (the set
// the skeleton function marks). From a surface point x with outward normal n, the caller
// follows x − τn inward to the first τ0 with s(x − τ0 n)·n = 0 and evaluates the feature
// tensor S there, eigenvalues λ1 ≤ λ2 ≤ λ3. Two readings follow:
//
//   h_mid = h0(1/(h0²λ3) − a) − a·h0·(λ1⁺ + λ2⁺)/(2λ3)        (mid_surface_thickness)
//
// the principal thickness at the mid-surface, without the diffusion offset that curvature
// adds (λ⁺ = max(λ, 0)): exact on a plate (λ1 = λ2 = 0), 2R + O(a·h0/κR) at the axis of a rod
// (λ2 = λ3: the offset ½·a·h0 removed) and at the centre of a ball (λ1 = λ2 = λ3: a·h0
// removed), and within 0.01 % of the wall of a tube, 0.1 % for a tube as thick as its bore
// (the across-wall eigenvalue alone: the others vanish on its mid-surface;
// tests/features/test_wall_thickness.cpp). Near a wall's rim the end face's source lowers λ3
// at the mid-surface, and h_mid reads too thick (up to +50 % at a quarter of the wall from a
// 4 mm plate's rim).
//
//   h_twice = 2·τ0                                            (twice the depth)
//
// exact on a flat wall up to its rims (the mid-surface of a symmetric wall stays in the
// middle however near the rim, because s·n is odd across it), but off by ±t²H/2 on a
// curved wall (H the mean curvature: the mid-surface of a harmonic field is not the
// geometric middle; ±7 % on the inner and outer skin of a 30/24 mm tube).
//
// Where a face of the opposite skin reaches the same mid-surface point, the two skins'
// separation across the wall (analysis/mid_surface_pairs.hpp) is exact on curved walls and
// tapers as well, and replaces h_twice. It also reads a wall where it meets another: there
// the mid-surface point lies in the junction, whose inscribed sphere is larger than either
// wall's, and h_mid reads up to +35 % (the outer corner of a 3 mm L-bracket, the plate at the
// foot of a rib), while the skins across the wall are still the wall's. Where h_mid exceeds
// the separation by more than kJunctionRatio, the separation is taken. A ball or a rod,
// whose mid-surface points gather at the centre or the axis, pairs faces up to
// arccos(kOppositeCosine) off the antipode, reading 2R·cos(θ/2) ≤ 2R; h_mid is exact there
// and stays within kJunctionRatio of that, so it is kept.
//
// wall_thickness() takes h_mid, the exact reading wherever the mid-surface point is a
// point of one wall, and turns to the rim reading where the field there still carries another
// surface's source: the part of s that is not across the wall, rim_indicator = |s(p0)| /
// |s(x)·n| (s(p0)·n = 0 by construction), is 0 inside a wall, a tube or at the centre of a
// rod, and 0.2–1.5 within half a wall of a rim. When h_twice is far above h_mid the search
// ran along the wall, not across it (from an end face, a rim face or a hole's wall, where
// h_twice is the length of the wall): neither reading is that face's wall — h_mid at such a
// p0 reads the wall's extent in its own plane, which near a corner of the part is small — and
// wall_thickness() gives NaN; the caller gives such faces their neighbours' value (the wall
// the rim bounds).

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "features/thickness.hpp"

namespace bemshape::features {

/// h_mid [model units] from the ascending eigenvalues of S at the mid-surface point (see
/// above); saturates at kMaxThicknessFactor·h0 where λ3 is not measurable.
inline double mid_surface_thickness(const Eigen::Vector3d& eigenvalues, double h0, double a) {
  const double lambda = eigenvalues(2);
  if (!(h0 * h0 * lambda > kMinInverseThickness)) return kMaxThicknessFactor * h0;
  const double offset =
      a * h0 * (std::max(eigenvalues(0), 0.0) + std::max(eigenvalues(1), 0.0)) / (2.0 * lambda);
  return std::max(0.0, h0 * (1.0 / (h0 * h0 * lambda) - a) - offset);
}

/// Rim indicators up to kRimFrom take h_mid alone, from kRimFull on h_twice alone, linearly
/// in between. Measured on the labelled parts (tests/support/labelled_parts.hpp): within a wall,
/// a tube or a rod the indicator stays below 0.05; at a quarter of the wall from a rim it is
/// 0.5–1, at half a wall 0.3, and h_mid is already within 1 % of the wall from where it
/// drops below 0.1.
inline constexpr double kRimFrom = 0.1;
inline constexpr double kRimFull = 0.3;
/// A reading above this multiple of the skins' separation (where a pair was found) is a
/// junction's: the separation is taken.
inline constexpr double kJunctionRatio = 1.05;
/// Near a rim without a pair, h_mid is kept where twice the depth agrees with it within this
/// fraction: the rim indicator is raised there by a taper, not by a rim (the skins of a
/// wedge of 20° are 160° apart, beyond the pairing's limit, and the taper's field along the
/// wall gives them indicators of 0.1–0.25; h_mid and 2τ0 agree within 2.5 % there and read
/// the wall through p0 within 2 %, tests/analysis/test_wall_thickness_shapes.cpp). Within
/// half a wall of a true rim h_mid reads 10–50 % above 2τ0. At 5 % the noisy faces near the
/// rims of the noisy L-bracket (σ 3 % of t) kept h_mid and read a second thin region
/// (tests/analysis/test_thickness_scale.cpp); 2.5 % keeps the wedge's readings and not those.
/// It applies below kRimFull only: in the wedge of a noisy convex edge a tilted face's search
/// finds a zero of s·n a fraction of the wall deep where h_mid and 2τ0 agree at that fraction
/// (0.29 on the 6 mm end of the σ = 3 % taper, rim indicator 2.5).
inline constexpr double kRimAgreement = 0.025;
/// h_twice above this multiple of h_mid means the search ran along the wall, not across it.
inline constexpr double kAlongWallRatio = 1.5;

/// The search direction −n and the field's across-wall direction e3 at p0 (the eigenvector of
/// λ3) must agree within 30°: a face whose search crosses its wall obliquely — a small face
/// on a noisy or chamfered edge, tilted halfway between two walls — reaches a zero of s·n
/// that is neither wall's middle, and twice its depth reads neither wall (a 3 mm L-bracket's
/// noisy outer edge: 2τ0 = 2.2).
inline constexpr double kMinAlignment = 0.866;

/// Whether the search crossed its wall obliquely (|n·e3| = `alignment` below kMinAlignment;
/// NaN, where e3 is not defined, never is).
inline bool oblique(double alignment) { return alignment < kMinAlignment; }

/// Whether the search ran along the wall rather than across it (twice the depth above
/// kAlongWallRatio·h_mid).
inline bool along_wall(double mid_thickness, double twice_depth) {
  return twice_depth > kAlongWallRatio * mid_thickness;
}

/// The weight of the rim reading: 0 up to kRimFrom, 1 from kRimFull on, linear between.
inline double rim_weight(double rim_indicator) {
  return std::clamp((rim_indicator - kRimFrom) / (kRimFull - kRimFrom), 0.0, 1.0);
}

/// The wall thickness of a face from its readings (see above) [model units]: h_mid inside a
/// wall (rim indicator up to kRimFrom); towards a rim, blended into the separation of the two
/// skins that share the mid-surface point (`pair_thickness`, analysis/mid_surface_pairs.hpp:
/// exact on flat and curved walls and tapers up to their rims), which alone is taken from
/// kRimFull on; the separation where h_mid exceeds it by more than kJunctionRatio (a
/// junction). NaN — the face takes its neighbours' reading — where neither is the face's own
/// wall: the search ran along the wall (`twice_depth` > kAlongWallRatio·h_mid) or crossed it
/// obliquely (`alignment`, see oblique()), or the face is near a rim (rim indicator above
/// kRimFrom), has no pair and its rim indicator is kRimFull or more or twice its depth is more
/// than kRimAgreement from h_mid (where it is within, a taper: h_mid). `twice_depth` may be
/// NaN (no mid-surface point found along the normal): h_mid is used.
inline double wall_thickness(double mid_thickness, double twice_depth, double rim_indicator,
                             double pair_thickness = std::numeric_limits<double>::quiet_NaN(),
                             double alignment = std::numeric_limits<double>::quiet_NaN()) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(twice_depth))
    return mid_thickness;
  if (along_wall(mid_thickness, twice_depth) || oblique(alignment))
    return nan;
  const bool paired = std::isfinite(pair_thickness);
  const double weight = rim_weight(rim_indicator);
  if (weight > 0.0 && !paired)
    return weight < 1.0 && std::abs(twice_depth - mid_thickness) <= kRimAgreement * mid_thickness
               ? mid_thickness
               : nan;
  const double reading =
      weight > 0.0 ? (1.0 - weight) * mid_thickness + weight * pair_thickness : mid_thickness;
  // Where walls meet, the pair's wall rather than the junction's larger sphere.
  if (paired && reading > kJunctionRatio * pair_thickness)
    return pair_thickness;
  return reading;
}

}  // namespace bemshape::features
