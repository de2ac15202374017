#pragma once
// Closed, outward-oriented triangulations of simple solids whose shape-feature PDE has a
// closed-form solution (ball, spherical shell, plate, rod). Used by the tests, the benchmark
// programs and the demo. All lengths are in model units.

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

/// Geodesic sphere: the icosahedron with each face split into frequency² triangles, vertices
/// projected onto the sphere |x − center| = radius. 20·frequency² faces, 10·frequency² + 2
/// vertices, mean edge ≈ 1.1·radius/frequency.
SurfaceMesh make_geodesic_sphere(double radius, int frequency,
                                 const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// Smallest geodesic-sphere frequency whose longest edge is at most `max_edge`.
int geodesic_frequency_for_edge(double radius, double max_edge);

/// Spherical shell R1 < |x| < R2: the outer sphere oriented outward and the inner sphere
/// oriented into the cavity (normals towards the centre), so both bound the solid.
SurfaceMesh make_spherical_shell(double inner_radius, double outer_radius, int inner_frequency,
                                 int outer_frequency);

/// Axis-aligned box [lo, hi], each face a structured grid of right triangles with edges no
/// longer than `max_edge` along the axes.
SurfaceMesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double max_edge);

/// Thin-walled box [−half, half] around the cavity [−(half − wall), half − wall] (every wall
/// `wall` thick): the outer box oriented outward and the inner one into the cavity, both as
/// make_box. InputError unless 0 < wall < the smallest half extent.
SurfaceMesh make_hollow_box(const Eigen::Vector3d& half, double wall, double max_edge);

/// Closed circular cylinder (rod) of the given radius along the z axis, z ∈ [−length/2,
/// length/2], with flat caps; edges about `max_edge` long.
SurfaceMesh make_cylinder(double radius, double length, double max_edge);

}  // namespace bemshape::geometry
