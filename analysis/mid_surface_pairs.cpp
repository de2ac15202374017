#include "analysis/mid_surface_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/point_bins.hpp"

namespace bemshape::analysis {
namespace {

/// Edge length of an equilateral triangle of the face's area: √(4A/√3).
double face_edge(double area) { return std::sqrt(4.0 * area / std::sqrt(3.0)); }

}  // namespace

MidSurfacePairs mid_surface_pairs(const geometry::SurfaceMesh& mesh,
                                  const Eigen::MatrixX3d& mid_point, const Eigen::VectorXd& depth,
                                  const FaceMask& wanted, const FaceMask& across) {
  const Eigen::Index nf = mesh.num_faces();
  MidSurfacePairs result;
  result.thickness.setConstant(nf, std::numeric_limits<double>::quiet_NaN());
  result.partner.setConstant(nf, -1);
  if (!wanted.any()) return result;
  // Cells of twice the mean edge: a query of the typical radius looks at 3³ cells.
  const double cell = 2.0 * face_edge(mesh.face_areas().mean());
  const PointBins grid(mid_point, across, cell);
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (!wanted(f) || !std::isfinite(depth(f))) continue;
    const Eigen::Vector3d p = mid_point.row(f).transpose();
    const Eigen::Vector3d n = mesh.face_normals().row(f).transpose();
    const double radius = 0.5 * depth(f) + 2.0 * face_edge(mesh.face_areas()(f));
    double nearest = radius * radius;
    Eigen::Index partner = -1;
    grid.near(p, radius, [&](Eigen::Index g) {
      if (mesh.face_normals().row(g).dot(n.transpose()) > -kOppositeCosine) return;
      const double d2 = (mid_point.row(g).transpose() - p).squaredNorm();
      if (d2 < nearest) {
        nearest = d2;
        partner = g;
      }
    });
    if (partner < 0) continue;
    // The skins' separation across the wall, along the bisector of the two normals.
    const Eigen::Vector3d m =
        (n - mesh.face_normals().row(partner).transpose()).normalized();
    const double separation =
        (mesh.face_centroids().row(f) - mesh.face_centroids().row(partner)).dot(m.transpose());
    // The two searches met: the skins lie on either side of the shared point, about as far
    // apart as their depths add up to (a coarse facet's centroid can sit behind its partner's).
    const double depths = depth(f) + depth(partner);
    if (!(separation >= kDepthAgreement * depths && separation <= depths / kDepthAgreement))
      continue;
    result.thickness(f) = separation;
    result.partner(f) = static_cast<int>(partner);
  }
  return result;
}

}  // namespace bemshape::analysis
