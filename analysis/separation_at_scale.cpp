#include "analysis/separation_at_scale.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace bemshape::analysis {

Eigen::VectorXd separation_at_scale(const geometry::SurfaceMesh& mesh,
                                    const Eigen::VectorXd& separation, double radius) {
  const Eigen::Index nf = mesh.num_faces();
  const Eigen::MatrixX3d& centroids = mesh.face_centroids();
  const Eigen::MatrixX3d& normals = mesh.face_normals();
  const Eigen::VectorXd& areas = mesh.face_areas();
  // The paired faces in cells of side `radius`: a disc's faces lie in the 27 cells around
  // its centre's.
  const Eigen::RowVector3d origin = centroids.colwise().minCoeff();
  const auto cell = [&](const Eigen::RowVector3d& c) {
    return ((c - origin) / radius).array().floor().cast<std::int64_t>().eval();
  };
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return std::uint64_t((i * 73856093) ^ (j * 19349663) ^ (k * 83492791));
  };
  std::unordered_map<std::uint64_t, std::vector<Eigen::Index>> cells;
  for (Eigen::Index f = 0; f < nf; ++f)
    if (std::isfinite(separation(f))) {
      const auto c = cell(centroids.row(f));
      cells[key(c(0), c(1), c(2))].push_back(f);
    }
  Eigen::VectorXd result = separation;
  const double r2 = radius * radius;
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (!std::isfinite(separation(f))) continue;
    const auto c = cell(centroids.row(f));
    double sum = 0.0, weight = 0.0;
    for (std::int64_t i = c(0) - 1; i <= c(0) + 1; ++i)
      for (std::int64_t j = c(1) - 1; j <= c(1) + 1; ++j)
        for (std::int64_t k = c(2) - 1; k <= c(2) + 1; ++k) {
          const auto it = cells.find(key(i, j, k));
          if (it == cells.end()) continue;
          for (const Eigen::Index g : it->second) {
            if ((centroids.row(g) - centroids.row(f)).squaredNorm() > r2) continue;
            if (normals.row(g).dot(normals.row(f)) < kSameSkinCosine) continue;
            sum += areas(g) * separation(g);
            weight += areas(g);
          }
        }
    result(f) = sum / weight;  // f itself is in its disc
  }
  return result;
}

}  // namespace bemshape::analysis
