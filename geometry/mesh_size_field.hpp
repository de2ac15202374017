#pragma once
// Target element size over the surface of a part, for a graded solver mesh (issue #32).
//
// The densities of the shape-feature PDE vary along a wall only where the geometry does —
// near creases, holes, thin walls and curvature — while on flat walls elements far larger
// than the default edge h_f = 1.5·a·h0 give the same thickness (a 4 mm plate at h0 = 3.6:
// median h_p 3.9944 at edge 1.08, 4.0002 at edge 2, 4.0008 at edge 4). The size field is the
// lower envelope of cones
//
//   h(x) = min( h_max, min over sources s of ( h_s + (g − 1)·dist(x, s) ) )
//
// with dist the Euclidean distance to a source (a point or segment) and the gradation g: two
// elements one element length apart differ in size by at most the factor g. The curvature
// sources may take a gentler g within their own size of them (SizeFieldParameters::
// curvature_gradation): they are the edges of a curved surface, and a face's middle lies a
// third of its size from them. The sources, each
// with the reason that sets it:
//
//   crease           every crease segment (surface_creases.hpp) whose dihedral angle is not
//                    a facet angle of a tessellated smooth surface: h_f
//   crease spacing   where two straight creases (maximal collinear crease chains) that share
//                    no corner come within l of each other, and at corners with a crease of
//                    length l: c_l·l — so that elements between close creases are not needles
//                    (a hole of 64 facets of 0.29 mm forces 0.29 mm edges along its rims)
//   thin wall        points of the surface whose wall, measured by a ray along −n against the
//                    surface, is thinner than t_thin (default h0): h_f
//   wall thickness   the same points with a wall t ≥ t_thin: c_t·t
//   curvature        smoothed edges and facet creases of tessellated smooth surfaces of radius
//                    ρ = w/θ: max(h_f, c_ρ·ρ)
//   chord            smoothed and nearly flat edges: h_δ, the longest chord that stays within
//                    the chord tolerance δ of the facets (surface_creases.hpp); with a
//                    chord-to-wall ratio c_δ the tolerance is c_δ times the wall under the edge
//                    (the ray along −n from its faces), so that a chord changes no wall by more
//                    than that fraction: a 3 mm tube keeps its round walls within 0.03 mm while
//                    a hole through a plate, whose wall across is the plate's extent, may be
//                    coarse
//
// The wall thickness from a ray is a geometric estimate for choosing element sizes only; the
// thickness the program reports comes from the PDE.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <utility>

#include "geometry/surface_creases.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

/// Gradation g (per element): the ratio of neighbouring element sizes the field allows.
/// Botsch–Kobbelt and CGAL's adaptive sizing use 1.2–1.5. TODO-measured: see
/// docs/benchmarks.md "Graded solver mesh".
inline constexpr double kDefaultGradation = 1.4;

/// h_max / h0 on flat walls. TODO-measured.
inline constexpr double kDefaultMaxEdgeRatio = 2.0;

/// c_t: elements no longer than this times the local wall thickness (walls ≥ t_thin).
inline constexpr double kWallThicknessEdgeRatio = 1.0;

/// c_ρ: elements no longer than this times the curvature radius of a tessellated smooth
/// surface (an element spans at most c_ρ radians of arc), never below h_f.
inline constexpr double kCurvatureEdgeRatio = 0.2;

/// c_l: elements no longer than this times the distance between two close creases.
inline constexpr double kCreaseSpacingEdgeRatio = 1.5;

/// Sizes are floored at this fraction of h_f by default (SizeFieldParameters::min_size).
/// Creases closer than that to each other (a boolean's leftovers: the CSG parts have crease edges of 0.004 mm beside their 0.7 mm facets,
/// and touching creases give a spacing of 0) are kept with what angles they allow instead of
/// refining without end; the remesher reports the smallest angle it reached.
inline constexpr double kMinSizeRatio = 1.0 / 16.0;


/// Walls are measured from this fraction of t_thin below the surface on: a nearer hit is the
/// roughness of a noisy surface (a scan), not a wall.
inline constexpr double kMinWallRatio = 0.1;

/// Spacing of the wall-thickness samples, as a fraction of h0.
inline constexpr double kThicknessSampleSpacing = 0.5;

enum class SizeReason : int {
  maximum = 0,
  crease,
  crease_spacing,
  thin_wall,
  wall_thickness,
  curvature,
  chord,
};
inline constexpr int kSizeReasons = 7;

/// "maximum", "crease", "crease spacing", "thin wall", "wall thickness", "curvature", "chord".
const char* to_string(SizeReason reason);

struct SizeFieldParameters {
  double fine_edge = 0.0;  ///< h_f [model units]: the default solver edge 1.5·a·h0
  double max_edge = 0.0;   ///< h_max [model units]
  double gradation = kDefaultGradation;  ///< g > 1
  /// g of the curvature sources within their own size of them, if in (1, g): a gentler
  /// growth away from the smoothed edges of a curved surface, whose sources are its edges,
  /// so that the size inside its faces stays near c_ρ·ρ; farther away they grow at g
  /// (≤ 0: g everywhere).
  double curvature_gradation = 0.0;
  /// t_thin [model units]: walls thinner than this get h_f; ≤ 0 turns the wall-thickness
  /// sources (thin wall and wall thickness) off.
  double thin_wall = 0.0;
  double wall_thickness_ratio = kWallThicknessEdgeRatio;      ///< c_t
  double curvature_ratio = kCurvatureEdgeRatio;               ///< c_ρ; ≤ 0: off
  double crease_spacing_ratio = kCreaseSpacingEdgeRatio;      ///< c_l
  /// h_min [model units]: no source asks for less; 0 means kMinSizeRatio·h_f.
  double min_size = 0.0;
  /// Spacing of the wall-thickness samples [model units] (> 0 when thin_wall > 0).
  double sample_spacing = 0.0;
  /// c_δ: the chord sources' tolerance is this times the wall under the edge (≤ 0: the
  /// tolerance the crossed edges were found with, surface_creases.hpp). Needs sample_spacing.
  double chord_thickness_ratio = 0.0;
  /// false: creases are sources of size h_max instead of h_f (a uniform field of h_max,
  /// bounded only by crease spacing and chords: the uniform remeshing mode).
  bool refine_creases = true;
};

/// Sources per reason and the range of their sizes.
struct SizeFieldSummary {
  std::array<long, kSizeReasons> sources{};
  std::array<double, kSizeReasons> smallest{};  ///< smallest h_s of each reason [model units]
  double min_size = 0.0;                        ///< smallest h over the sources [model units]
};

class MeshSizeField {
 public:
  /// Field of `mesh` (closed, outward) with its creases; throws InputError for parameters
  /// that are not positive and finite, or h_f > h_max, g ≤ 1.
  MeshSizeField(const SurfaceMesh& mesh, const SurfaceCreases& creases,
                const SizeFieldParameters& parameters);
  /// A constant field h everywhere (no sources).
  explicit MeshSizeField(double size);
  ~MeshSizeField();
  MeshSizeField(MeshSizeField&&) noexcept;
  MeshSizeField& operator=(MeshSizeField&&) noexcept;

  /// h(x) [model units] and the reason of the source that sets it. Thread-safe.
  std::pair<double, SizeReason> size_and_reason(const Eigen::Vector3d& x) const;
  double size(const Eigen::Vector3d& x) const { return size_and_reason(x).first; }

  double max_edge() const;
  double gradation() const;
  const SizeFieldSummary& summary() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bemshape::geometry
