#include "geometry/isotropic_remeshing.hpp"

#include <cmath>
#include <sstream>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "geometry/detail/cgal_mesh_algorithms.hpp"

namespace bemshape::geometry {
namespace {

/// Area of an equilateral triangle of unit edge, √3/4: faces ≈ area / (this·h²).
constexpr double kEquilateralArea = 0.4330127018922193;

}  // namespace

SurfaceMesh refine_to_edge_length(const SurfaceMesh& mesh, double target_edge,
                                  const RemeshingOptions& options,
                                  const ProgressCallback& progress) {
  if (!(std::isfinite(target_edge) && target_edge > 0.0)) {
    std::ostringstream msg;
    msg << "target edge length " << target_edge << " must be a positive number";
    throw InputError(msg.str());
  }
  if (mesh.empty())
    throw InputError("cannot remesh an empty mesh");
  const double estimate = mesh.area() / (kEquilateralArea * target_edge * target_edge);
  if (estimate > options.max_faces) {
    std::ostringstream msg;
    msg << "target edge length " << target_edge << " would create about " << std::llround(estimate)
        << " faces (limit " << std::llround(options.max_faces) << "): choose a larger edge length";
    throw ResourceError(msg.str());
  }
  throw_if_cancelled();
  report_progress(progress, "remeshing", 0.0);
  detail::CgalRemeshParameters parameters;
  parameters.target_edge = target_edge;
  parameters.sharp_angle_degrees = options.sharp_angle_degrees;
  parameters.iterations = options.iterations;
  parameters.max_edge = options.max_edge_ratio * target_edge;
  detail::CgalRemeshResult result =
      detail::cgal_isotropic_remesh(mesh.vertices(), mesh.faces(), parameters);
  throw_if_cancelled();
  report_progress(progress, "remeshing", 1.0);
  return SurfaceMesh(std::move(result.vertices), std::move(result.faces));
}

}  // namespace bemshape::geometry
