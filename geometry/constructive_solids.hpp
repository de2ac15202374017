#pragma once
// Solids built the way CAD parts are: prisms (extruded polygons, boxes, faceted cylinders)
// combined by union and difference. The labelled parts (tests/support/labelled_parts.hpp), the tests and
// the benchmarks build their parts with known walls from these.
//
// Every mesh here is closed and outward-oriented; lengths in model units. The Booleans are
// CGAL's corefinement (exact predicates): operands must be closed, manifold and free of
// self-intersections, and should not touch only along an edge or a vertex.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "geometry/surface_mesh.hpp"

namespace bemshape::geometry {

/// Simple polygon in the plane, #P×2 corners counter-clockwise [model units].
using Polygon2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;

/// The polygon swept along z from z0 to z1 (z0 < z1): caps triangulated by ear clipping, each
/// side a rectangle of two triangles. InputError if the polygon has fewer than 3 corners,
/// is not counter-clockwise or is not simple enough for ear clipping.
SurfaceMesh extrude_polygon(const Polygon2& polygon, double z0, double z1);

/// Axis-aligned box [lo, hi] as 12 triangles.
SurfaceMesh make_box_solid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// Circle of the given radius about `centre`, as a regular polygon of `segments` corners
/// (the first at angle `phase` [rad]): the faceted circles CAD exports write.
Polygon2 circle_polygon(const Eigen::Vector2d& centre, double radius, int segments,
                        double phase = 0.0);

/// Faceted cylinder with axis along z through `centre` (x, y), z ∈ [z0, z1].
SurfaceMesh make_faceted_cylinder(const Eigen::Vector2d& centre, double radius, double z0,
                                  double z1, int segments);

/// The mesh moved by the rigid motion (or any orientation-preserving affine map) `motion`.
SurfaceMesh transformed(const SurfaceMesh& mesh, const Eigen::Affine3d& motion);

/// A ∪ B and A \ B.
SurfaceMesh mesh_union(const SurfaceMesh& a, const SurfaceMesh& b);
SurfaceMesh mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b);

}  // namespace bemshape::geometry
