#pragma once
// A flat triangular boundary element with the geometry every panel integral needs,
// computed once per mesh (bem/quadrature/panel_integrals.hpp reads nothing else).
//
// Conventions: corners a, b, c in the face's vertex order; the unit normal
// n = (b − a) × (c − a) / |…| follows the right-hand rule, which is outward for bemshape
// meshes (geometry/surface_mesh.hpp). The in-plane frame (t1, t2, n) is right-handed with
// t1 = (b − a)/|b − a|, t2 = n × t1. All lengths in model units.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::bem {

struct Panel {
  std::array<Eigen::Vector3d, 3> corners;  ///< a, b, c
  Eigen::Vector3d edge1;                   ///< b − a
  Eigen::Vector3d edge2;                   ///< c − a
  Eigen::Vector3d normal;                  ///< unit right-hand-rule normal n
  Eigen::Vector3d tangent1;                ///< t1 = (b − a)/|b − a|
  Eigen::Vector3d tangent2;                ///< t2 = n × t1
  Eigen::Vector3d centroid;                ///< (a + b + c)/3
  double area = 0;                         ///< |T| [model units²]
  double diameter = 0;                     ///< longest edge [model units]
  double radius = 0;  ///< max corner distance from the centroid: |x − y| ≥ |x − centroid| − radius
};

/// The Euclidean distance from x to the closed triangle (the nearest point may be inside,
/// on an edge or at a corner) [model units].
double distance_to_panel(const Panel& panel, const Eigen::Vector3d& x);

/// The panel of triangle (a, b, c). Throws InputError for a degenerate (zero-area) triangle.
Panel make_panel(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// One panel per face of `mesh`, in face order. Throws InputError naming the first face of
/// zero area (run mesh repair first).
std::vector<Panel> make_panels(const geometry::SurfaceMesh& mesh);

}  // namespace bemshape::bem
