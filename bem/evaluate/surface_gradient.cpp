#include "bem/evaluate/surface_gradient.hpp"

#include <vector>

#include <Eigen/QR>

namespace bemshape::bem {
namespace {

/// Faces around each vertex (compressed rows: faces of vertex v are
/// faces[offsets[v] .. offsets[v+1])).
struct VertexStars {
  std::vector<Eigen::Index> offsets, faces;
};

VertexStars vertex_stars(const geometry::SurfaceMesh& mesh) {
  VertexStars stars;
  stars.offsets.assign(static_cast<size_t>(mesh.num_vertices()) + 1, 0);
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) ++stars.offsets[static_cast<size_t>(mesh.faces()(f, k)) + 1];
  for (size_t v = 0; v + 1 < stars.offsets.size(); ++v) stars.offsets[v + 1] += stars.offsets[v];
  stars.faces.resize(static_cast<size_t>(stars.offsets.back()));
  std::vector<Eigen::Index> fill(stars.offsets.begin(), stars.offsets.end() - 1);
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      stars.faces[static_cast<size_t>(fill[static_cast<size_t>(mesh.faces()(f, k))]++)] = f;
  return stars;
}

}  // namespace

Eigen::MatrixX3d reconstruct_vertex_values(const geometry::SurfaceMesh& mesh,
                                           const Eigen::MatrixX3d& face_values) {
  const VertexStars stars = vertex_stars(mesh);
  Eigen::MatrixX3d values = Eigen::MatrixX3d::Zero(mesh.num_vertices(), 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    const auto begin = stars.offsets[static_cast<size_t>(v)];
    const auto end = stars.offsets[static_cast<size_t>(v) + 1];
    const Eigen::Index m = end - begin;
    if (m == 0) continue;  // an unreferenced vertex carries no data
    const Eigen::RowVector3d xv = mesh.vertices().row(v);
    // Tangent plane of the star: the area-weighted normal, frame (t1, t2) orthogonal to it.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double scale = 0.0;
    for (auto t = begin; t < end; ++t) {
      const Eigen::Index f = stars.faces[static_cast<size_t>(t)];
      normal += mesh.face_areas()(f) * mesh.face_normals().row(f).transpose();
      scale = std::max(scale, (mesh.face_centroids().row(f) - xv).norm());
    }
    if (!(normal.norm() > 0.0)) normal = Eigen::Vector3d::UnitZ();
    normal.normalize();
    if (!(scale > 0.0)) scale = 1.0;
    const Eigen::Vector3d t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
    // φ(c_f) ≈ φ_v + b1·t1·(c_f − x_v) + b2·t2·(c_f − x_v), offsets scaled by the star size.
    Eigen::MatrixXd design(m, 3);
    Eigen::MatrixXd rhs(m, 3);
    for (Eigen::Index r = 0; r < m; ++r) {
      const Eigen::Index f = stars.faces[static_cast<size_t>(begin + r)];
      const Eigen::Vector3d offset = (mesh.face_centroids().row(f) - xv).transpose() / scale;
      design(r, 0) = 1.0;
      design(r, 1) = t1.dot(offset);
      design(r, 2) = t2.dot(offset);
      rhs.row(r) = face_values.row(f);
    }
    values.row(v) = design.colPivHouseholderQr().solve(rhs).row(0);
  }
  return values;
}

SurfaceGradient interior_surface_gradient(const geometry::SurfaceMesh& mesh,
                                          const BoundarySolution& solution) {
  SurfaceGradient out;
  out.vertex_values = reconstruct_vertex_values(mesh, solution.phi);
  const Eigen::Index nf = mesh.num_faces();
  out.face_gradient.resize(nf, 9);
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Eigen::Vector3d n = mesh.face_normals().row(f).transpose();
    const double twice_area = 2.0 * mesh.face_areas()(f);
    Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();  // grad(i, j) = ∂s_i/∂x_j
    if (twice_area > 0.0) {
      for (int k = 0; k < 3; ++k) {
        // ∇λ_k = n × (x_{k+2} − x_{k+1}) / (2|T|): gradient of the barycentric coordinate.
        const Eigen::Vector3d edge = mesh.corner(f, (k + 2) % 3) - mesh.corner(f, (k + 1) % 3);
        const Eigen::Vector3d grad_lambda = n.cross(edge) / twice_area;
        grad += out.vertex_values.row(mesh.faces()(f, k)).transpose() * grad_lambda.transpose();
      }
    }
    grad += solution.q.row(f).transpose() * n.transpose();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out.face_gradient(f, 3 * i + j) = grad(i, j);
  }
  out.vertex_gradient = Eigen::MatrixXd::Zero(mesh.num_vertices(), 9);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (Eigen::Index f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index v = mesh.faces()(f, k);
      out.vertex_gradient.row(v) += mesh.face_areas()(f) * out.face_gradient.row(f);
      weight(v) += mesh.face_areas()(f);
    }
  }
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (weight(v) > 0.0) out.vertex_gradient.row(v) /= weight(v);
  return out;
}

}  // namespace bemshape::bem
