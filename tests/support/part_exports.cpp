#include "tests/support/part_exports.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "geometry/isotropic_remeshing.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::testing {

geometry::SurfaceMesh refined_to_faces(const geometry::SurfaceMesh& mesh, long min_faces) {
  // A uniform remesh to edge h gives about area / (0.43·h²) faces (docs/geometry.md); the
  // creases kept along the facets add some, so the first edge is usually enough, and each
  // retry shrinks it by the square root of the shortfall.
  if (mesh.num_faces() >= min_faces) return mesh;
  double edge = std::sqrt(mesh.area() / (0.43 * double(min_faces)));
  for (int attempt = 0;; ++attempt) {
    geometry::SurfaceMesh fine = geometry::refine_to_edge_length(mesh, edge);
    if (fine.num_faces() >= min_faces || attempt == 4) return fine;
    edge *= std::sqrt(double(fine.num_faces()) / double(min_faces)) * 0.95;
  }
}

LabelledPart fine_export(const std::string& name, long min_faces) {
  LabelledPart part = make_labelled_part(name, kFineExportSegments);
  // Welded and validated as a file of the part would be before it is refined.
  geometry::TriangleSoup soup;
  soup.vertices = part.mesh.vertices();
  soup.faces = part.mesh.faces();
  soup.format = "triangle arrays";
  soup.corners_in_file = static_cast<std::size_t>(3 * soup.faces.rows());
  part.mesh = refined_to_faces(geometry::prepare_triangle_soup(soup, name).mesh, min_faces);
  return part;
}

geometry::SurfaceMesh with_normal_noise(const geometry::SurfaceMesh& mesh, double sigma,
                                        std::uint64_t seed) {
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(mesh.num_vertices(), 3);
  Eigen::VectorXd shortest =
      Eigen::VectorXd::Constant(mesh.num_vertices(), std::numeric_limits<double>::infinity());
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      normals.row(mesh.faces()(f, k)) += mesh.face_areas()(f) * mesh.face_normals().row(f);
      const double edge = (mesh.corner(f, (k + 1) % 3) - mesh.corner(f, k)).norm();
      for (const int j : {k, (k + 1) % 3})
        shortest(mesh.faces()(f, j)) = std::min(shortest(mesh.faces()(f, j)), edge);
    }
  std::mt19937_64 generator(seed);
  // Uniform in (0, 1]: 53 random bits, never 0 (the logarithm below).
  const auto uniform = [&generator] { return (double(generator() >> 11) + 1.0) * 0x1.0p-53; };
  Eigen::MatrixX3d vertices = mesh.vertices();
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    const double norm = normals.row(v).norm();
    if (!(norm > 0.0)) continue;
    const double gaussian =
        std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * std::numbers::pi * uniform());
    // No vertex moves by more than kMaxNoiseEdgeFraction of its shortest edge, so that the
    // noise never folds the surface through itself (a scan is rough, not self-crossing).
    const double shift = std::clamp(sigma * gaussian, -kMaxNoiseEdgeFraction * shortest(v),
                                    kMaxNoiseEdgeFraction * shortest(v));
    vertices.row(v) += shift / norm * normals.row(v);
  }
  return geometry::SurfaceMesh(vertices, mesh.faces());
}

}  // namespace bemshape::testing
