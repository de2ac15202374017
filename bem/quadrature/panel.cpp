#include "bem/quadrature/panel.hpp"

#include <algorithm>
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
