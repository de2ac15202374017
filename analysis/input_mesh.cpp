#include "analysis/input_mesh.hpp"

#include "core/errors.hpp"
#include "geometry/mesh_io.hpp"

namespace bemshape::analysis {

namespace {

/// The arrays as the soup a reader would give. Throws InputError for non-finite positions and
/// indices out of range.
geometry::TriangleSoup triangle_soup(const Eigen::Ref<const Eigen::MatrixX3d>& V,
                                     const Eigen::Ref<const Eigen::MatrixX3i>& F,
                                     const std::string& name) {
  if (!V.allFinite())
    throw InputError(name + ": vertex positions must be finite numbers");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw InputError(name + ": face vertex indices must lie in [0, " + std::to_string(V.rows()) +
                     ") (0-based)");
  geometry::TriangleSoup soup;
  soup.vertices = V;
  soup.faces = F;
  soup.format = "triangle arrays";
  soup.corners_in_file = static_cast<std::size_t>(3 * F.rows());
  return soup;
}

}  // namespace

geometry::PreparedMesh inspect_triangles(const Eigen::Ref<const Eigen::MatrixX3d>& V,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& F,
                                         const std::string& name,
                                         const ProgressCallback& progress) {
  return geometry::inspect_triangle_soup(triangle_soup(V, F, name), name, {}, progress);
}

geometry::PreparedMesh prepare_triangles(const Eigen::Ref<const Eigen::MatrixX3d>& V,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& F,
                                         const std::string& name,
                                         const ProgressCallback& progress) {
  return geometry::prepare_triangle_soup(triangle_soup(V, F, name), name, {}, progress);
}

}  // namespace bemshape::analysis
