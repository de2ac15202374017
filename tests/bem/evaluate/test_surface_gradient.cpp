// The surface gradient ∇s = ∇_Γφ + q n from P0 boundary data of known fields.
#include <catch2/catch.hpp>

#include "bem/evaluate/surface_gradient.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {
// P0 boundary data of the affine field u(x) = c + B x (component i = row i of B): φ at the
// centroids and the exact normal derivative q = B n.
bem::BoundarySolution affine_data(const geometry::SurfaceMesh& mesh, const Eigen::Matrix3d& b,
                                  const Eigen::Vector3d& c) {
  bem::BoundarySolution sol;
  sol.phi = (mesh.face_centroids() * b.transpose()).rowwise() + c.transpose();
  sol.q = mesh.face_normals() * b.transpose();
  return sol;
}

Eigen::Matrix3d face_gradient(const bem::SurfaceGradient& g, Eigen::Index f) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = g.face_gradient(f, 3 * i + j);
  return m;
}
}  // namespace

TEST_CASE("affine fields are reproduced exactly on flat parts of a box") {
  Eigen::Matrix3d b;
  b << 1.0, 0.2, -0.3, 0.5, 2.0, 0.1, -0.4, 0.3, 0.7;
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  const auto box = geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.1);
  const auto g = bem::interior_surface_gradient(box, affine_data(box, b, c));
  int checked = 0;
  for (Eigen::Index f = 0; f < box.num_faces(); ++f) {
    // Faces whose vertices are all at least one cell away from the box's edges.
    bool interior = true;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = box.corner(f, k);
      int on_boundary_planes = 0;
      for (int d = 0; d < 3; ++d)
        if (v(d) < 0.05 || v(d) > 0.95) ++on_boundary_planes;
      interior = interior && on_boundary_planes <= 1;
    }
    if (!interior) continue;
    CHECK((face_gradient(g, f) - b).norm() < 1e-12 * b.norm());
    ++checked;
  }
  CHECK(checked > 500);
}

TEST_CASE("vertex values reproduce affine data on a flat star and converge on a sphere") {
  Eigen::Matrix3d b = Eigen::Matrix3d::Identity();
  double previous = 1.0, previous_trace = 1.0, trace_error = 0.0;
  for (int n : {4, 8, 16}) {
    const auto sphere = geometry::make_geodesic_sphere(0.5, n);
    const auto sol = affine_data(sphere, b, Eigen::Vector3d::Zero());
    const Eigen::MatrixX3d v = bem::reconstruct_vertex_values(sphere, sol.phi);
    const double error = (v - sphere.vertices()).rowwise().norm().maxCoeff() / 0.5;
    CHECK(error < previous / 3.0);  // second order
    previous = error;
    // The divergence of the reconstructed gradient of x on the sphere: exactly 3 in the limit,
    // converging at second order.
    const auto g = bem::interior_surface_gradient(sphere, sol);
    trace_error = 0.0;
    for (Eigen::Index f = 0; f < sphere.num_faces(); ++f)
      trace_error = std::max(trace_error, std::abs(face_gradient(g, f).trace() - 3.0) / 3.0);
    INFO("n = " << n << ": max relative error of div " << trace_error);
    CHECK(trace_error < previous_trace / 3.0);
    previous_trace = trace_error;
  }
  CHECK(trace_error < 0.01);
}

TEST_CASE("per-vertex gradients are area-weighted means of the adjacent faces") {
  const auto sphere = geometry::make_geodesic_sphere(1.0, 3);
  Eigen::Matrix3d b;
  b << 0.3, 0.0, 0.1, 0.0, -0.2, 0.4, 0.5, 0.1, 0.0;
  const auto g = bem::interior_surface_gradient(sphere, affine_data(sphere, b, Eigen::Vector3d::Zero()));
  const Eigen::Index v = sphere.faces()(0, 0);
  Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(9);
  double area = 0.0;
  for (Eigen::Index f = 0; f < sphere.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (sphere.faces()(f, k) == v) {
        sum += sphere.face_areas()(f) * g.face_gradient.row(f);
        area += sphere.face_areas()(f);
      }
  CHECK((g.vertex_gradient.row(v) - sum / area).norm() < 1e-14);
}
