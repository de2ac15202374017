#pragma once
// Remeshing of a closed surface to a size field h(x) (mesh_size_field.hpp): the graded
// solver mesh of issue #32, and the uniform mesh as the special case of a constant field.
//
// Botsch & Kobbelt, "A remeshing approach to multiresolution modeling" (SGP 2004), with the
// target length a field: edges longer than 4/3·h(midpoint) are split, edges shorter than
// 4/5·h collapsed (unless that makes an edge longer than 4/3·h), edges flipped towards the
// ideal valences (a vertex's total angle over 60°), vertices relaxed in the tangent plane and
// put back onto the input faces of their patch. CGAL 5.5's isotropic_remeshing takes a single
// target length (a sizing field came with CGAL 6.0), hence this remesher.
//
// Guarantees, for a closed, outward mesh as returned by prepare_mesh_file:
//   * the output is closed, manifold and outward (Euler operations with the link condition);
//   * every vertex lies on the input surface: on an input crease, or on an input face of its
//     patch (closest point, to rounding);
//   * every crease of the input (surface_creases.hpp) is a union of output edges: crease
//     edges are only split at their midpoints, crease corners never move, a vertex inside a
//     straight crease only slides along it, crease edges are never flipped or collapsed
//     across. With no smoothed edges the output surface IS the input surface: volume and area
//     equal to rounding;
//   * no operation but a split makes a face whose smallest angle is below min(min_angle, the
//     smallest angle of the faces it replaces), or turns a face's normal by more than
//     max_normal_turn: a good triangle is never made bad, a bad one (a CAD sliver, a split's
//     child) only better. The smallest angle reached is reported; where the input's creases
//     themselves meet at a small angle, no triangulation can do better than that angle.
//   * Failures of this remesher are reported as bemshape's (InternalError), never as a
//     defect of the input.

#include <Eigen/Core>
#include <array>

#include "core/progress.hpp"
#include "geometry/mesh_size_field.hpp"
#include "geometry/surface_creases.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

/// The angle [degrees] that collapses, flips and moves keep every new face above (unless the
/// faces they replace were already worse). TODO-measured.
inline constexpr double kMinAngleBoundDegrees = 20.0;

struct GradedRemeshingOptions {
  /// Split/collapse/flip/relax rounds; the graded field converges in about as many rounds as
  /// it has size doublings between its smallest and largest element. TODO-measured.
  unsigned iterations = 8;
  double min_angle_degrees = kMinAngleBoundDegrees;
  /// Largest rotation of a face's normal by a collapse, flip or move [degrees]: on a flat
  /// patch any fold turns it by 180°; on a smoothed curved patch faces turn by h/ρ ≪ 30°.
  double max_normal_turn_degrees = 30.0;
  /// Refuse to grow beyond this many faces (ResourceError).
  double max_faces = 2.0e7;
  /// If > 0, edges longer than this times h are split at the end, so that none is longer
  /// (the uniform mode's promise of RemeshingOptions::max_edge_ratio); 0 leaves the edges
  /// of the rescue (up to about 1.6·h, where a collapse made a bad triangle good).
  double max_edge_ratio = 0.0;
};

struct GradedMeshReport {
  Eigen::Index faces = 0, vertices = 0;
  double min_edge = 0.0, max_edge = 0.0, mean_edge = 0.0;  ///< [model units]
  double min_angle_degrees = 0.0;   ///< smallest interior angle of any face
  double max_edge_ratio = 0.0;      ///< max over edges of length / h(midpoint)
  double min_edge_ratio = 0.0;      ///< min over edges of length / h(midpoint)
  /// Area of the output faces whose size h(centroid) is set by each reason [model units²].
  std::array<double, kSizeReasons> area_by_reason{};
  /// Σ area_f / (√3/4·h(centroid_f)²): the faces the field asks for on this surface.
  double field_faces = 0.0;
  Eigen::Vector3d worst_angle_at = Eigen::Vector3d::Zero();  ///< centroid of the worst face
  /// The input was kept as it is (GradedMeshParameters::keep_input_face_ratio).
  bool kept_input = false;
  int creases = 0;         ///< crease edges of the input
  int smoothed_edges = 0;  ///< candidate creases smoothed (tessellated smooth surfaces)
  long splits = 0, collapses = 0, flips = 0, moves = 0;
  SizeFieldSummary field;
};

struct GradedMesh {
  SurfaceMesh mesh;
  GradedMeshReport report;
};

/// Remeshes `mesh` (closed, outward) with creases `creases` to the size field `field`.
/// Throws InputError if the mesh is not a closed manifold, ResourceError beyond
/// options.max_faces, InternalError if the result has a degenerate face (a failure of this
/// remesher, never of the input).
GradedMesh remesh_to_size_field(const SurfaceMesh& mesh, const SurfaceCreases& creases,
                                const MeshSizeField& field,
                                const GradedRemeshingOptions& options = {},
                                const ProgressCallback& progress = {});

/// Area of an equilateral triangle of unit edge, √3/4: a face of size h covers this·h², so a
/// surface of area A asks for about A/(this·h²) faces.
inline constexpr double kEquilateralArea = 0.4330127018922193;

/// An input finer than the field asks by less than this factor in face count is kept rather
/// than coarsened: the user's own well-shaped triangles (a generated ball, a mesh from another
/// solver) read better than a remeshed surface of fewer faces. The 81,920-face geodesic sphere
/// (R 1, h0 0.1, `--measure paper`) asks for 32,244 faces at 3/κ: remeshed to 38,640 its h_f
/// is 3.2 % off at its worst vertex, kept (2.54 times the faces asked) 0.26 %
/// (docs/validation.md, "Surface values on a large sphere"); at a factor of 2 it was remeshed.
inline constexpr double kKeepInputFaceRatio = 3.0;

/// The parameters of the graded solver mesh of a part, in terms of the PDE's h0.
struct GradedMeshParameters {
  double h0 = 0.0;         ///< characteristic length [model units]
  double fine_edge = 0.0;  ///< h_f: the uniform rule's edge 1.5·a·h0 [model units]
  double max_edge_ratio = kDefaultMaxEdgeRatio;  ///< h_max = this·h0
  double gradation = kDefaultGradation;
  /// SizeFieldParameters::curvature_gradation (≤ 0: gradation).
  double curvature_gradation = 0.0;
  /// t_thin = this·h0: walls thinner than that get h_f.
  double thin_wall_ratio = 1.0;
  double wall_thickness_ratio = kWallThicknessEdgeRatio;  ///< c_t
  double curvature_ratio = kCurvatureEdgeRatio;           ///< c_ρ
  double crease_spacing_ratio = kCreaseSpacingEdgeRatio;  ///< c_l
  /// Creases ask for h_f (surface values resolved along every edge of the part); false: the
  /// elements along a crease follow the other sources (the wall reading, read half a wall
  /// deep, does not need the surface's edge layers resolved).
  bool refine_creases = true;
  /// No source asks for less than this times h_f (SizeFieldParameters::min_size): creases
  /// closer than that (a boolean's leftovers, CAD slivers) are kept as they are, with the
  /// angles they allow, instead of refining around them.
  double min_size_ratio = kMinSizeRatio;
  double crease_angle_degrees = 1.0;  ///< θ_c (--sharp-angle)
  /// θ_s: facet angles of tessellated smooth surfaces up to this may be smoothed
  /// (surface_creases.hpp); 0 keeps every crease. TODO-measured.
  double smooth_angle_degrees = 15.0;
  /// δ = this·h0: the chord tolerance of smoothed surfaces. TODO-measured.
  double chord_tolerance_ratio = 2e-3;
  /// Facets are smoothed only where the chord they allow, h_δ, is at least this times h_f
  /// (CreaseOptions::min_chord): 1 keeps the facets where even the fine elements would fall
  /// more than δ below them; 0 smooths every tessellated smooth surface (elements of h_δ
  /// instead of the crease spacing of its facets).
  double min_chord_ratio = 1.0;
  /// c_δ: if > 0, the chord tolerance is c_δ times the wall under each smoothed edge instead
  /// of δ (SizeFieldParameters::chord_thickness_ratio).
  double chord_thickness_ratio = 0.0;
  /// If > 0, creases and tessellations are found from the face normals filtered at this
  /// times h0 (CreaseOptions::normal_scale): a noisy surface's edges at that scale.
  double normal_scale_ratio = 0.0;
  /// CreaseOptions::require_facet_strips.
  bool require_facet_strips = true;
  /// CreaseOptions::curve_turn_degrees: crease vertices turning by at most this [degrees]
  /// (round rims) may slide along their crease or be dropped; 0 keeps every turn a corner.
  double curve_turn_degrees = 0.0;
  /// An input whose edges are all within 4/3 of the field's h, whose angles are all above
  /// remeshing.min_angle_degrees and whose face count is at most this times the count the
  /// field asks for is returned as it is (0: always remesh).
  double keep_input_face_ratio = kKeepInputFaceRatio;
  GradedRemeshingOptions remeshing;
};

/// Creases, size field and remeshing of a part for the solver (issue #32).
GradedMesh graded_solver_mesh(const SurfaceMesh& mesh, const GradedMeshParameters& parameters,
                              const ProgressCallback& progress = {});

}  // namespace bemshape::geometry
