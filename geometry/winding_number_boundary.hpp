#pragma once
// The solid a closed surface that crosses itself encloses, and its boundary: the set of
// points of positive winding number,
//
//   Ω₊ = { x : w(x) ≥ 1 },   w(x) = (1/4π) Σ_f Ω_f(x)   (winding_number.hpp),
//
// the interior under the positive fill rule of the 3MF core specification (§4.1.1), which
// slicers print and which the union of overlapping bodies already follows
// (surface_repair.hpp). Its boundary is made of pieces of the given surface, so nothing is
// moved or invented:
//
//   1. the surface is split along the curves where it crosses itself (CGAL's
//      autorefinement): no two pieces cross any more, and each piece has one winding number
//      on each side, w_back = w_front + 1 (its normal points to the front);
//   2. the winding numbers are propagated exactly: across a piece they step by one, and
//      around an edge where k pieces meet (k = 4 where two sheets cross) the pieces, in the
//      order of their angle about the edge (exact orientation predicates), bound wedges on
//      which w is constant; one generalized winding number per connected set of pieces fixes
//      the constant;
//   3. the boundary of Ω₊ is every piece with w_front ≤ 0 < w_back, kept with its
//      orientation (outward).
//
// Pieces that coincide (coplanar overlaps) add their steps; where two pieces meet an edge
// in one half-plane (sheets lying on each other), the order about the edge is undefined, and
// the surface is moved by a generic perturbation of kGenericPerturbation of its size and
// split again (simulation of simplicity). What the region was and how much of it was
// counted more than once or as negative is reported, so that the caller can tell a clear
// case — sheets overlapping (w = 2), as bodies of one shell that were not united — from a
// surface turned inside out somewhere (w ≤ −1: a fold, a patch pushed through the opposite
// wall), whose intended solid cannot be told.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string>

namespace bemshape::geometry {

/// The displacement of every vertex, relative to the bounding-box diagonal, when sheets lie
/// exactly on each other: 1e-9 is ten million float64 steps, so every coincidence is broken,
/// and a thousand times below the weld tolerance (kWeldRelativeTolerance), so no length
/// the analysis resolves changes.
inline constexpr double kGenericPerturbation = 1e-9;

struct WindingNumberBoundary {
  /// The boundary of Ω₊, outward oriented [model units]; may have edges of four faces where
  /// Ω₊ touches itself along a curve (split_nonmanifold separates them).
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  bool ok = false;
  /// Why the pieces could not be labelled (ok == false).
  std::string failure;
  /// ∫ w dV: the input's signed volume, overlaps counted as often as they are covered
  /// [model units³].
  double signed_volume = 0.0;
  /// |Ω₊|, |{w ≥ 2}| and |{w ≤ −1}| [model units³].
  double volume = 0.0;
  double overlap_volume = 0.0;
  double negative_volume = 0.0;
  /// Smallest and largest winding number next to the surface.
  int min_winding = 0;
  int max_winding = 0;
  /// Edges of the curves along which the surface crosses itself, and their bounding box.
  std::size_t curve_edges = 0;
  Eigen::AlignedBox3d curves;
  /// Bounding box of the pieces next to a winding number other than 0 and 1: the overlaps
  /// and the places where the surface is inside out.
  Eigen::AlignedBox3d irregular;
  /// Input faces the curves split.
  std::size_t faces_split = 0;
  /// The surface was perturbed (kGenericPerturbation) because sheets lay on each other.
  bool perturbed = false;
};

/// Ω₊ of the closed, consistently oriented surface (at most two faces per edge, one fan per
/// vertex; vertices #V×3 [model units], faces #F×3) as described above. With refine =
/// false the surface is not split (nor perturbed): its faces must not cross, but may lie
/// exactly on each other and meet in any number along an edge (welded bodies sharing faces);
/// it must be closed as a chain (the faces' oriented edges cancel). Never throws for the
/// surface's geometry (ok == false with the reason); throws CancelledError when the run is
/// cancelled.
WindingNumberBoundary winding_number_boundary(const Eigen::MatrixX3d& vertices,
                                              const Eigen::MatrixX3i& faces, bool refine = true);

}  // namespace bemshape::geometry
