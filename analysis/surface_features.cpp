#include "analysis/surface_features.hpp"

#include <limits>
#include <vector>

#include "bem/evaluate/surface_gradient.hpp"
#include "features/point_features.hpp"
#include "geometry/closest_point.hpp"

namespace bemshape::analysis {
namespace {

Eigen::MatrixXd feature_columns(const features::FeatureField<3>& field) {
  Eigen::MatrixXd values(field.f_h.size(), kFeatureColumns);
  values.col(kColumnFh) = field.f_h;
  values.col(kColumnHf) = field.h_f;
  values.col(kColumnHp) = field.h_p;
  values.middleCols(kColumnNf, 3) = field.n_f;
  values.col(kColumnWall).setConstant(std::numeric_limits<double>::quiet_NaN());
  return values;
}

void renormalise_orientation(Eigen::MatrixXd& values) {
  for (Eigen::Index r = 0; r < values.rows(); ++r) {
    auto n = values.row(r).segment<3>(kColumnNf);
    const double length = n.norm();
    if (length > 0.0)
      n /= length;
  }
}

}  // namespace

SurfaceFeatures surface_features(const geometry::SurfaceMesh& solver_mesh,
                                 const bem::BoundarySolution& solution,
                                 const features::FeatureParameters& parameters) {
  const bem::SurfaceGradient gradient = bem::interior_surface_gradient(solver_mesh, solution);
  const std::vector<char> faces_inside(static_cast<std::size_t>(solver_mesh.num_faces()), 1);
  const std::vector<char> vertices_inside(static_cast<std::size_t>(solver_mesh.num_vertices()), 1);
  SurfaceFeatures result;
  // Face gradient: mean of the corner vertex gradients (see the header for why).
  Eigen::MatrixXd face_gradient(solver_mesh.num_faces(), 9);
  for (Eigen::Index f = 0; f < solver_mesh.num_faces(); ++f)
    face_gradient.row(f) = (gradient.vertex_gradient.row(solver_mesh.faces()(f, 0)) +
                            gradient.vertex_gradient.row(solver_mesh.faces()(f, 1)) +
                            gradient.vertex_gradient.row(solver_mesh.faces()(f, 2))) /
                           3.0;
  result.face = feature_columns(
      features::compute_features<3>(solution.phi, face_gradient, faces_inside, parameters));
  result.vertex = feature_columns(features::compute_features<3>(
      gradient.vertex_values, gradient.vertex_gradient, vertices_inside, parameters));
  return result;
}

SurfaceFeatures transfer_features(const geometry::SurfaceMesh& solver_mesh,
                                  const SurfaceFeatures& solver_features,
                                  const geometry::SurfaceMesh& target) {
  SurfaceFeatures result;
  const geometry::ClosestPointQuery on_solver(solver_mesh);

  // Vertices: barycentric interpolation on the closest solver face.
  const geometry::ClosestPoints at_vertices = on_solver.closest_points(target.vertices());
  result.vertex.resize(target.num_vertices(), kFeatureColumns);
  for (Eigen::Index v = 0; v < target.num_vertices(); ++v) {
    const Eigen::Index f = at_vertices.faces(v);
    result.vertex.row(v).setZero();
    for (int k = 0; k < 3; ++k)
      result.vertex.row(v) +=
          at_vertices.barycentric(v, k) * solver_features.vertex.row(solver_mesh.faces()(f, k));
  }

  // Faces: area-weighted mean over the solver faces whose centroids land on each face.
  const geometry::ClosestPointQuery on_target(target);
  const geometry::ClosestPoints owners = on_target.closest_points(solver_mesh.face_centroids());
  result.face = Eigen::MatrixXd::Zero(target.num_faces(), kFeatureColumns);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(target.num_faces());
  for (Eigen::Index f = 0; f < solver_mesh.num_faces(); ++f) {
    const double area = solver_mesh.face_areas()(f);
    result.face.row(owners.faces(f)) += area * solver_features.face.row(f);
    weight(owners.faces(f)) += area;
  }
  std::vector<Eigen::Index> orphans;
  for (Eigen::Index f = 0; f < target.num_faces(); ++f) {
    if (weight(f) > 0.0)
      result.face.row(f) /= weight(f);
    else
      orphans.push_back(f);
  }
  if (!orphans.empty()) {
    Eigen::MatrixX3d centroids(static_cast<Eigen::Index>(orphans.size()), 3);
    for (std::size_t i = 0; i < orphans.size(); ++i)
      centroids.row(static_cast<Eigen::Index>(i)) = target.face_centroids().row(orphans[i]);
    const geometry::ClosestPoints nearest = on_solver.closest_points(centroids);
    for (std::size_t i = 0; i < orphans.size(); ++i)
      result.face.row(orphans[i]) =
          solver_features.face.row(nearest.faces(static_cast<Eigen::Index>(i)));
  }
  renormalise_orientation(result.vertex);
  renormalise_orientation(result.face);
  return result;
}

}  // namespace bemshape::analysis
