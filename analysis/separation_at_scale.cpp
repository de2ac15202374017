#include "analysis/separation_at_scale.hpp"

#include <cmath>

#include "analysis/point_bins.hpp"

namespace bemshape::analysis {

Eigen::VectorXd separation_at_scale(const geometry::SurfaceMesh& mesh,
                                    const Eigen::VectorXd& separation, double radius) {
  const Eigen::Index nf = mesh.num_faces();
  const Eigen::MatrixX3d& centroids = mesh.face_centroids();
  const Eigen::MatrixX3d& normals = mesh.face_normals();
  const Eigen::VectorXd& areas = mesh.face_areas();
  const PointBins paired(centroids, separation.array().isFinite(), radius);
  Eigen::VectorXd result = separation;
  const double r2 = radius * radius;
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (!std::isfinite(separation(f))) continue;
    double sum = 0.0, weight = 0.0;
    paired.near(centroids.row(f).transpose(), radius, [&](Eigen::Index g) {
      if ((centroids.row(g) - centroids.row(f)).squaredNorm() > r2) return;
      if (normals.row(g).dot(normals.row(f)) < kSameSkinCosine) return;
      sum += areas(g) * separation(g);
      weight += areas(g);
    });
    result(f) = sum / weight;  // f itself is in its disc
  }
  return result;
}

}  // namespace bemshape::analysis
