#include "geometry/bilateral_normals.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bemshape::geometry {

Eigen::MatrixX3d bilateral_face_normals(const SurfaceMesh& mesh, double scale,
                                        double range_sigma) {
  const Eigen::Index nf = mesh.num_faces(), nv = mesh.num_vertices();
  Eigen::MatrixX3d normals = mesh.face_normals();
  if (nf == 0 || !(scale > 0.0)) return normals;
  // Faces around each vertex, then each face's vertex neighbours (itself included), each once.
  std::vector<std::vector<int>> around(static_cast<std::size_t>(nv));
  for (Eigen::Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) around[std::size_t(mesh.faces()(f, k))].push_back(int(f));
  std::vector<std::vector<int>> ring(static_cast<std::size_t>(nf));
  Eigen::VectorXd perimeter(nf);
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < nf; ++f) {
    std::vector<int>& r = ring[std::size_t(f)];
    perimeter(f) = 0.0;
    for (int k = 0; k < 3; ++k) {
      const auto& faces = around[std::size_t(mesh.faces()(f, k))];
      r.insert(r.end(), faces.begin(), faces.end());
      perimeter(f) += (mesh.corner(f, (k + 1) % 3) - mesh.corner(f, k)).norm();
    }
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  // Summed in one thread: the same σ_s, and so the same normals, whatever the thread count.
  const double sigma = perimeter.sum() / (3.0 * double(nf));
  if (!(sigma > 0.0)) return normals;
  const int sweeps =
      std::clamp(int(std::ceil((scale / sigma) * (scale / sigma))), 1, kMaxBilateralSweeps);
  const double spatial = 1.0 / (2.0 * sigma * sigma), range = 1.0 / (2.0 * range_sigma * range_sigma);
  Eigen::MatrixX3d next(nf, 3);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < nf; ++i) {
      const Eigen::RowVector3d ni = normals.row(i);
      if (ni.squaredNorm() == 0.0) {
        next.row(i) = ni;
        continue;
      }
      const Eigen::RowVector3d ci = mesh.face_centroids().row(i);
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      for (const int j : ring[std::size_t(i)]) {
        const double d2 = (mesh.face_centroids().row(j) - ci).squaredNorm();
        const double x2 = (normals.row(j) - ni).squaredNorm();
        sum += mesh.face_areas()(j) * std::exp(-spatial * d2 - range * x2) * normals.row(j);
      }
      const double norm = sum.norm();
      next.row(i) = norm > 0.0 ? Eigen::RowVector3d(sum / norm) : ni;
    }
    normals.swap(next);
  }
  return normals;
}

}  // namespace bemshape::geometry
