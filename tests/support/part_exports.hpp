#pragma once
// A labelled part as the file a user would measure: the fine tessellation a CAD export gives
// (round holes and walls faceted at a 0.01 mm chord tolerance, every face refined to at least
// a given count), and seeded noisy copies of it, as a 3-D scan or a coarse export gives.
// Fixtures of the wall-thickness tests and of bench_thickness_tools, where bemshape and the
// tools it is compared with read the same file.

#include <cstdint>
#include <string>

#include "geometry/surface_mesh.hpp"
#include "tests/support/labelled_parts.hpp"

namespace bemshape::testing {

/// Faces of the fine tessellation a thickness tool is compared on: what an export at a
/// 0.01 mm chord tolerance gives for parts with holes and round walls.
inline constexpr long kFineExportFaces = 50000;

/// Facets per full circle of a fine export: at 64 the 10 mm holes of the labelled parts are
/// within 0.006 mm of their circle, the 30 mm tube (twice the facets) within 0.005 mm
/// (make_labelled_part facets the tube twice as finely).
inline constexpr int kFineExportSegments = 64;

/// `mesh` (closed) refined uniformly (geometry::refine_to_edge_length, every crease and
/// facet kept) to at least `min_faces` triangles: the same surface, a finer triangulation.
geometry::SurfaceMesh refined_to_faces(const geometry::SurfaceMesh& mesh, long min_faces);

/// The part `name` (make_labelled_part) with kFineExportSegments facets per circle, its
/// surface refined uniformly (geometry::refine_to_edge_length, every crease and facet kept)
/// to at least `min_faces` triangles: the same solid, the same labels, a finer triangulation.
LabelledPart fine_export(const std::string& name, long min_faces = kFineExportFaces);

/// A noisy vertex moves by at most this fraction of its shortest edge.
inline constexpr double kMaxNoiseEdgeFraction = 0.25;

/// `mesh` with every vertex moved along its area-weighted vertex normal by an independent
/// Gaussian of standard deviation `sigma` [model units] (at most kMaxNoiseEdgeFraction of the
/// vertex's shortest edge: only the few vertices of a CAD sliver move less), from a generator seeded with `seed`
/// (the same seed gives the same copy on every machine: the normal variates come from
/// std::mt19937_64 by the Box–Muller transform, not from a library distribution). A labelled
/// part's labels still apply to the noisy copy's faces while sigma is small against its walls.
geometry::SurfaceMesh with_normal_noise(const geometry::SurfaceMesh& mesh, double sigma,
                                        std::uint64_t seed);

}  // namespace bemshape::testing
