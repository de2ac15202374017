#include "geometry/surface_mesh.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "core/errors.hpp"

namespace bemshape::geometry {

SurfaceMesh::SurfaceMesh(Eigen::MatrixX3d vertices, Eigen::MatrixX3i faces)
    : vertices_(std::move(vertices)), faces_(std::move(faces)) {
  for (Eigen::Index v = 0; v < vertices_.rows(); ++v) {
    if (!vertices_.row(v).allFinite()) {
      std::ostringstream msg;
      msg << "vertex " << v << " has a non-finite coordinate (" << vertices_(v, 0) << ", "
          << vertices_(v, 1) << ", " << vertices_(v, 2) << ")";
      throw InputError(msg.str());
    }
  }
  const Eigen::Index nv = vertices_.rows();
  for (Eigen::Index f = 0; f < faces_.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (faces_(f, k) < 0 || faces_(f, k) >= nv) {
        std::ostringstream msg;
        msg << "face " << f << " refers to vertex " << faces_(f, k) << " but the mesh has " << nv
            << " vertices";
        throw InputError(msg.str());
      }
    }
  }
  const Eigen::Index nf = faces_.rows();
  normals_.resize(nf, 3);
  areas_.resize(nf);
  centroids_.resize(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double twice_area = cross.norm();
    areas_(f) = 0.5 * twice_area;
    const Eigen::Vector3d normal =
        twice_area > 0.0 ? Eigen::Vector3d(cross / twice_area) : Eigen::Vector3d::Zero();
    normals_.row(f) = normal.transpose();
    centroids_.row(f) = ((a + b + c) / 3.0).transpose();
  }
}

BoundingBox SurfaceMesh::bounding_box() const {
  BoundingBox box;
  if (vertices_.rows() == 0)
    return box;
  box.min = vertices_.colwise().minCoeff().transpose();
  box.max = vertices_.colwise().maxCoeff().transpose();
  return box;
}

double SurfaceMesh::signed_volume() const {
  double volume = 0.0;
  for (Eigen::Index f = 0; f < faces_.rows(); ++f)
    volume += corner(f, 0).dot(corner(f, 1).cross(corner(f, 2)));
  return volume / 6.0;
}

double SurfaceMesh::max_edge_length() const {
  double longest = 0.0;
  for (Eigen::Index f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (corner(f, (k + 1) % 3) - corner(f, k)).norm());
  return longest;
}

double SurfaceMesh::smallest_angle_degrees() const {
  double smallest = 180.0;
  for (Eigen::Index f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = corner(f, (k + 1) % 3) - corner(f, k);
      const Eigen::Vector3d w = corner(f, (k + 2) % 3) - corner(f, k);
      smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi);
    }
  return smallest;
}

double SurfaceMesh::mean_edge_length() const {
  if (faces_.rows() == 0)
    return 0.0;
  double sum = 0.0;
  for (Eigen::Index f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      sum += (corner(f, (k + 1) % 3) - corner(f, k)).norm();
  return sum / (3.0 * static_cast<double>(faces_.rows()));
}

SurfaceMesh transformed(const SurfaceMesh& mesh, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation, double scale) {
  Eigen::MatrixX3d v =
      (scale * mesh.vertices() * rotation.transpose()).rowwise() + translation.transpose();
  return SurfaceMesh(std::move(v), mesh.faces());
}

SurfaceMesh with_flipped_orientation(const SurfaceMesh& mesh) {
  Eigen::MatrixX3i f = mesh.faces();
  f.col(1).swap(f.col(2));
  return SurfaceMesh(mesh.vertices(), std::move(f));
}

SurfaceMesh concatenated(const SurfaceMesh& a, const SurfaceMesh& b) {
  Eigen::MatrixX3d v(a.num_vertices() + b.num_vertices(), 3);
  v << a.vertices(), b.vertices();
  Eigen::MatrixX3i f(a.num_faces() + b.num_faces(), 3);
  f << a.faces(), (b.faces().array() + static_cast<int>(a.num_vertices())).matrix();
  return SurfaceMesh(std::move(v), std::move(f));
}

}  // namespace bemshape::geometry
