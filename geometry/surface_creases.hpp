#pragma once
// Creases of a closed triangle mesh: the edges a remesher must keep exactly so that the
// remeshed surface is the input surface, and the patches they bound.
//
// The dihedral angle of an edge is θ = ∠(n₁, n₂) ∈ [0, π] between the outward normals of its
// two faces (0 where the faces are coplanar). An edge is a crease candidate if θ > θ_c (the
// crease angle, `--sharp-angle`, default 1°: every edge that is not nearly flat).
//
// Tessellated smooth surfaces. A CAD export writes a cylinder of radius ρ as N planar facets
// of width w = 2ρ·sin(π/N), each turning by θ = 2π/N against the next: a 30 mm tube of 128
// facets has a 2.8° crease every 0.74 mm. Kept as creases, these force elements no wider than
// a facet (needles where the elements are longer). A candidate edge is *smoothed* (crossed by
// the remesher; its vertices then still lie on the input facets, its chords fall below them)
// when both hold:
//
//   1. it lies on a tessellated smooth surface: θ ≤ θ_s (the smooth angle) and each of the two
//      planar facets it separates (maximal sets of faces joined by edges with θ ≤ θ_c) borders
//      at least two different facets across edges with θ_c < θ ≤ θ_s — a facet strip of a
//      cylinder or fillet has a neighbour on each side, while the big flat faces on the two
//      sides of a lone small-angle crease (a draft angle, a shallow kink) do not;
//   2. the geometry allows it: a chord of length h crossing the edge falls at most
//        sag(h) = h·θ/4            for h ≤ 2w (it crosses one facet edge),
//        sag(h) = h²·θ/(8w)        for h > 2w (it crosses h/w edges of a surface of radius
//                                              ρ = w/θ, the arc sagitta h²/(8ρ)),
//      below the facets, w the narrower facet's width 2·area/(its candidate edges' length);
//      the longest chord within the chord tolerance δ, h_δ = sag⁻¹(δ), must be at least
//      `min_chord` (the solver's fine edge 1.5·a·h0): where even the fine elements would fall
//      further than δ below the facets, keeping the facets as creases is both exact and no
//      finer.
//
// The remesher limits the elements near a smoothed edge to h_δ (mesh_size_field.hpp), so the
// remeshed surface stays within δ of the input everywhere.

#include <Eigen/Core>
#include <vector>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

struct CreaseOptions {
  /// θ_c [degrees]: edges with a larger dihedral angle are creases unless smoothed.
  double crease_angle_degrees = 1.0;
  /// θ_s [degrees]: largest facet angle of a tessellated smooth surface that may be smoothed;
  /// 0 keeps every candidate as a crease (the surface is then the input surface exactly).
  double smooth_angle_degrees = 0.0;
  /// δ [model units]: largest sag of a remeshed chord below the facets it crosses.
  double chord_tolerance = 0.0;
  /// Smallest useful chord [model units]: an edge is smoothed only if h_δ ≥ this.
  double min_chord = 0.0;
  /// If > 0, the dihedral angles are those of the face normals filtered at this scale [model
  /// units] (bilateral_normals.hpp): the edges and tessellations of a noisy surface (a scan,
  /// a coarse export) at that scale, not the tilts of its facets. 0: the faces' own normals.
  double normal_scale = 0.0;
  /// Rule 1 above (a facet strip on both sides) for smoothing; false smooths every candidate
  /// up to θ_s the chord tolerance allows, lone shallow kinks too (with normals filtered at a
  /// scale, a tessellated ball's facets merge in places, and the strips break up), and the
  /// candidates whose two faces are one facet (joined around the candidate's ends), with the
  /// distance between the two faces' centroids as w: the filtered normals of a fine export's
  /// round jump by 5–9° at some of its facet edges and not at the next, and kept as creases
  /// those jumps were short creases about a millimetre apart, each asking for elements that
  /// small (plate_holes' rounded bottom edge).
  bool require_facet_strips = true;
  /// If > 0 [degrees]: a crease vertex where exactly two creases meet and turn by at most
  /// this (a round rim, tessellated as a polygon of short creases) is *curved*: the remesher
  /// may slide it along the crease, drop it or add vertices on the crease polygon, so that the
  /// rim's elements follow the size field rather than its tessellation; the chords across the
  /// dropped vertices are limited like those of a smoothed edge (`crossed`). 0: every vertex
  /// where a crease turns is a corner that never moves.
  double curve_turn_degrees = 0.0;
};

/// An edge of the input mesh, by its vertex indices (a < b), with its dihedral angle.
struct DihedralEdge {
  int a = 0, b = 0;
  double angle = 0.0;  ///< θ [rad]
  /// A facet edge of a tessellated smooth surface (rule 1 above) kept because the chord
  /// tolerance did not allow smoothing it; facet_width is then w [model units].
  bool tessellated = false;
  double facet_width = 0.0;
};

/// A non-crease edge with a dihedral angle, and what limits chords across it.
struct CrossedEdge {
  int a = 0, b = 0;
  double angle = 0.0;        ///< θ [rad]
  /// w [model units]: the narrower adjacent facet; inside a facet the lower face's height, and
  /// with CreaseOptions::normal_scale at least that scale (filtered normals turn over no less).
  double facet_width = 0.0;
  double max_chord = 0.0;    ///< h_δ = sag⁻¹(δ) [model units]; +∞ if δ = 0 was not asked for
  bool smoothed = false;     ///< a crease candidate (θ > θ_c) smoothed by the rule above
  int f0 = -1, f1 = -1;      ///< the two faces of the edge
};

struct SurfaceCreases {
  std::vector<DihedralEdge> creases;
  /// Non-crease edges with θ > kCurvedEdgeAngle (smoothed candidates and the nearly flat
  /// edges of finely tessellated curved surfaces), for the size field's curvature and chord
  /// limits; and the curved crease vertices v (a = b = v, θ the crease's turn there, w the
  /// mean of its two crease edges, f0 and f1 the faces of one of them), whose chords sag
  /// like those across a facet edge.
  std::vector<CrossedEdge> crossed;
  Eigen::VectorXi crease_degree;  ///< #V: number of creases at each vertex
  /// #V: crease vertices that never move or vanish: where creases end, branch or turn (a
  /// vertex with two collinear creases lies inside a straight crease and may slide along it).
  std::vector<char> corner;
  /// #V: the corners that are curved (CreaseOptions::curve_turn_degrees): corners of the
  /// creases' straight pieces for the size field, free to slide along the crease polygon in
  /// the remesher. All 0 unless asked for.
  std::vector<char> curved;
  Eigen::VectorXi face_patch;  ///< #F: patch index (faces joined without crossing a crease)
  int patches = 0;
  /// #F×3: the normals the dihedral angles were measured with (the faces' own, or filtered
  /// at CreaseOptions::normal_scale), for the wall-thickness rays of the size field.
  Eigen::MatrixX3d normals;
  int smoothed_edges() const;
};

/// Angles below this [rad] (1e-4 rad, 0.006°) carry no curvature worth sizing for: a chord of
/// length h across such an edge sags by at most h·θ/4 < 2.5e-5·h.
inline constexpr double kCurvedEdgeAngle = 1e-4;

/// Creases, smoothed edges and patches of a closed, consistently oriented mesh (as returned by
/// prepare_mesh_file). Throws InputError if an edge does not have exactly two faces.
SurfaceCreases find_surface_creases(const SurfaceMesh& mesh, const CreaseOptions& options = {});

/// h_δ: the longest chord whose sag (above) across an edge of angle θ [rad] between facets of
/// width w stays within δ; +∞ for θ = 0.
double longest_chord_within(double angle, double facet_width, double chord_tolerance);

}  // namespace bemshape::geometry
