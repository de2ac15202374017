#include "bem/quadrature/panel.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "core/errors.hpp"

namespace bemshape::bem {
namespace {

/// A triangle whose area is below this fraction of its squared longest edge has no usable
/// normal (its corners are collinear to rounding); it must be removed by mesh repair.
constexpr double degenerate_area_ratio = 1e-14;

}  // namespace

Panel make_panel(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Panel p;
  p.corners = {a, b, c};
  p.edge1 = b - a;
  p.edge2 = c - a;
  const Eigen::Vector3d cross = p.edge1.cross(p.edge2);
  const double twice_area = cross.norm();
  p.diameter = std::max({p.edge1.norm(), p.edge2.norm(), (c - b).norm()});
  if (!(twice_area > 2.0 * degenerate_area_ratio * p.diameter * p.diameter)) {
    std::ostringstream msg;
    msg << "degenerate triangle with corners (" << a.transpose() << "), (" << b.transpose()
        << "), (" << c.transpose() << "): zero area; repair the mesh first";
    throw InputError(msg.str());
  }
  p.area = 0.5 * twice_area;
  p.normal = cross / twice_area;
  p.tangent1 = p.edge1.normalized();
  p.tangent2 = p.normal.cross(p.tangent1);
  p.centroid = (a + b + c) / 3.0;
  p.radius = std::max({(a - p.centroid).norm(), (b - p.centroid).norm(), (c - p.centroid).norm()});
  return p;
}

double distance_to_panel(const Panel& panel, const Eigen::Vector3d& x) {
  // Barycentric-region test on the corners a, b, c: the nearest point is the foot of the
  // perpendicular when it falls inside, otherwise the nearest point of the nearest edge.
  const Eigen::Vector3d w = x - panel.corners[0];
  const double d = w.dot(panel.normal);
  const Eigen::Vector3d in_plane = w - d * panel.normal;
  // Coordinates (s, t) of the foot in the basis edge1, edge2 (Gram system).
  const double e11 = panel.edge1.squaredNorm(), e22 = panel.edge2.squaredNorm();
  const double e12 = panel.edge1.dot(panel.edge2);
  const double b1 = in_plane.dot(panel.edge1), b2 = in_plane.dot(panel.edge2);
  const double det = e11 * e22 - e12 * e12;
  const double s = (b1 * e22 - b2 * e12) / det, t = (b2 * e11 - b1 * e12) / det;
  if (s >= 0.0 && t >= 0.0 && s + t <= 1.0) return std::abs(d);
  const auto to_segment = [&x](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    const Eigen::Vector3d pq = q - p;
    const double u = std::clamp((x - p).dot(pq) / pq.squaredNorm(), 0.0, 1.0);
    return (x - p - u * pq).squaredNorm();
  };
  const auto& c = panel.corners;
  return std::sqrt(std::min({to_segment(c[0], c[1]), to_segment(c[1], c[2]), to_segment(c[2], c[0])}));
}

std::vector<Panel> make_panels(const geometry::SurfaceMesh& mesh) {
  std::vector<Panel> panels;
  panels.reserve(static_cast<size_t>(mesh.num_faces()));
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    try {
      panels.push_back(make_panel(mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)));
    } catch (const InputError& e) {
      throw InputError("face " + std::to_string(f) + ": " + e.what());
    }
  }
  return panels;
}

}  // namespace bemshape::bem
