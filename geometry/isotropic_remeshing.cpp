#include "geometry/isotropic_remeshing.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "geometry/detail/cgal_mesh_algorithms.hpp"
#include "geometry/mesh_size_field.hpp"
#include "geometry/surface_creases.hpp"

namespace bemshape::geometry {
namespace {

/// The size floor of the uniform mode is kMinSizeRatio times the smaller of h and this
/// fraction of the part's diagonal (a boolean's 0.004 mm leftover creases are not resolved,
/// the facets of a hole are, whatever h).
constexpr double kFloorDiagonalFraction = 0.01;

/// A face whose smallest angle is below this [degrees] is degenerate: CGAL's remeshing made
/// (29, 0, 0), (28, 0, 0), (27, 0, 0) from a 120 × 80 × 4 plate at edge 8.
constexpr double kDegenerateAngleDegrees = 1e-3;

/// Throws InputError for a target that is not a positive length or an empty mesh,
/// ResourceError when the target would create more than max_faces faces.
void check_target(const SurfaceMesh& mesh, double target_edge, double max_faces) {
  if (!(std::isfinite(target_edge) && target_edge > 0.0)) {
    std::ostringstream msg;
    msg << "target edge length " << target_edge << " must be a positive number";
    throw InputError(msg.str());
  }
  if (mesh.empty())
    throw InputError("cannot remesh an empty mesh");
  const double estimate = mesh.area() / (kEquilateralArea * target_edge * target_edge);
  if (estimate > max_faces) {
    std::ostringstream msg;
    msg << "target edge length " << target_edge << " would create about " << std::llround(estimate)
        << " faces (limit " << std::llround(max_faces) << "): choose a larger edge length";
    throw ResourceError(msg.str());
  }
}

}  // namespace

bool fine_enough(const SurfaceMesh& mesh, double target_edge) {
  // The graded remesher's rule for keeping its input (graded_remeshing.hpp), with no edge
  // above the target instead of 4/3 of it.
  return !mesh.empty() && mesh.max_edge_length() <= target_edge &&
         double(mesh.num_faces()) <=
             kKeepInputFaceRatio * mesh.area() / (kEquilateralArea * target_edge * target_edge) &&
         mesh.smallest_angle_degrees() >= kMinAngleBoundDegrees;
}

GradedMesh refine_uniformly(const SurfaceMesh& mesh, double target_edge,
                            const RemeshingOptions& options, const ProgressCallback& progress) {
  check_target(mesh, target_edge, options.max_faces);
  throw_if_cancelled();
  CreaseOptions crease_options;
  crease_options.crease_angle_degrees = options.sharp_angle_degrees;
  const SurfaceCreases creases = find_surface_creases(mesh, crease_options);
  // The constant field h, bounded only where creases are closer than h.
  SizeFieldParameters field_parameters;
  field_parameters.fine_edge = target_edge;
  field_parameters.max_edge = target_edge;
  field_parameters.curvature_ratio = 0.0;
  field_parameters.refine_creases = false;
  // Floored as the size field floors a fine mesh, not at a fraction of a coarse h: a hole's
  // facets (0.9 mm beside 68 mm edges on plate_holes) then still get elements as wide as they
  // are tall instead of 10° slivers.
  field_parameters.min_size =
      kMinSizeRatio * std::min(target_edge, kFloorDiagonalFraction * mesh.bounding_box().diagonal());
  const MeshSizeField field(mesh, creases, field_parameters);
  GradedRemeshingOptions remeshing;
  remeshing.max_faces = options.max_faces;
  remeshing.max_edge_ratio = options.max_edge_ratio;
  return remesh_to_size_field(mesh, creases, field, remeshing, progress);
}

SurfaceMesh refine_to_edge_length(const SurfaceMesh& mesh, double target_edge,
                                  const RemeshingOptions& options,
                                  const ProgressCallback& progress) {
  check_target(mesh, target_edge, options.max_faces);
  throw_if_cancelled();
  report_progress(progress, "remeshing", 0.0);
  if (fine_enough(mesh, target_edge)) {
    report_progress(progress, "remeshing", 1.0);
    return mesh;
  }
  detail::CgalRemeshParameters parameters;
  parameters.target_edge = target_edge;
  parameters.sharp_angle_degrees = options.sharp_angle_degrees;
  parameters.iterations = options.iterations;
  parameters.max_edge = options.max_edge_ratio * target_edge;
  detail::CgalRemeshResult result =
      detail::cgal_isotropic_remesh(mesh.vertices(), mesh.faces(), parameters);
  throw_if_cancelled();
  SurfaceMesh refined(std::move(result.vertices), std::move(result.faces));
  // CGAL's remeshing can leave a degenerate triangle at coarse sizes; the graded remesher's
  // constant field never does (its guards keep every angle near 20°).
  if (refined.smallest_angle_degrees() < kDegenerateAngleDegrees)
    return refine_uniformly(mesh, target_edge, options, progress).mesh;
  report_progress(progress, "remeshing", 1.0);
  return refined;
}

}  // namespace bemshape::geometry
