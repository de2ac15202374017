#pragma once
// Uniform surface refinement for the solver: remeshing to one target edge length h with the
// creases of the part kept exactly. Every output vertex lies on the input triangles (up to
// rounding), so the geometry — volume, area, creases — is the input's; only the
// triangulation changes.
//
//   refine_to_edge_length   CGAL's Polygon_mesh_processing::isotropic_remeshing (Botsch &
//                           Kobbelt, SGP 2004) with the sharp edges constrained: the mesh of
//                           --max-edge (an input already that fine and well shaped is kept). Constrained creases are only split, so a strip between
//                           two close creases becomes needles; where CGAL leaves a degenerate
//                           triangle (coarse sizes), the result of refine_uniformly instead.
//   refine_uniformly        the graded remesher (graded_remeshing.hpp) with the constant size
//                           field h, refined below h only where two creases come closer than h
//                           (a crease spacing l asks for c_l·l, mesh_size_field.hpp), so that
//                           keeping them needs no needle: no angle below about 20° at any h.

#include "core/progress.hpp"
#include "geometry/graded_remeshing.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

struct RemeshingOptions {
  /// Dihedral angle [degrees] above which an edge is a crease: it is kept (only split at
  /// midpoints, never flipped or collapsed) and its corners never move. The default 1° keeps
  /// every crease of the input, so the refined surface IS the input surface (volume and area
  /// unchanged to rounding): only exactly or nearly coplanar triangles, such as the slivers of
  /// a CAD plate, are merged and retriangulated. Raising it (e.g. 30°) lets the remesher cut
  /// across the facets of finely tessellated curved surfaces for better-shaped triangles, at
  /// the price of chords below the facets (plate_holes at h = 6: 30° changes the volume by
  /// −0.3 % and moves the surface by up to 1 mm; 1° changes neither).
  double sharp_angle_degrees = 1.0;
  /// Split/collapse/flip/relax rounds of CGAL's remeshing (CGAL's default is 1; more rounds
  /// even out the edge lengths around long CAD slivers, at a cost linear in the count);
  /// refine_uniformly runs GradedRemeshingOptions::iterations.
  unsigned iterations = 5;
  /// Edges longer than max_edge_ratio·h left by the remesher are split at the end, so the
  /// result satisfies longest edge ≤ max_edge_ratio·h.
  double max_edge_ratio = 1.3;
  /// Refuse targets that would create more faces than this (≈ area / (0.43 h²)).
  double max_faces = 2.0e7;
};

/// Remeshes a closed, outward-oriented mesh (as returned by prepare_mesh_file) to edge
/// length ≈ target_edge [model units], with the remesher's report (edge range, smallest
/// angle). Returns a closed, outward mesh whose longest edge is ≤
/// options.max_edge_ratio·target_edge and whose vertices lie on the input surface. Throws
/// InputError if target_edge is not positive and finite or the mesh is not closed,
/// ResourceError if the estimated face count exceeds options.max_faces.
GradedMesh refine_uniformly(const SurfaceMesh& mesh, double target_edge,
                            const RemeshingOptions& options = {},
                            const ProgressCallback& progress = {});

/// Whether `mesh` is already what remeshing to target_edge aims at, and is kept as it is: no
/// edge longer than target_edge, no angle below 20°, at most kKeepInputFaceRatio times the
/// faces of the target (area/(kEquilateralArea·target_edge²)). A geodesic sphere given with
/// --max-edge at or above its longest edge is solved on its own triangles.
bool fine_enough(const SurfaceMesh& mesh, double target_edge);

/// The same by CGAL's isotropic remeshing (the mesh only), or by refine_uniformly where CGAL
/// leaves a degenerate triangle; `mesh` itself where it is fine_enough.
SurfaceMesh refine_to_edge_length(const SurfaceMesh& mesh, double target_edge,
                                  const RemeshingOptions& options = {},
                                  const ProgressCallback& progress = {});

}  // namespace bemshape::geometry
