#pragma once
// Internal: CGAL's corefinement Booleans behind plain Eigen arrays, so that CGAL is compiled
// in one translation unit (cgal_boolean_operations.cpp). Use geometry/boolean_operations.hpp.

#include <Eigen/Core>

namespace bemshape::geometry::detail {

enum class BooleanOperation { union_of, difference };

/// CGAL::Polygon_mesh_processing::corefine_and_compute_union / _difference of two closed,
/// outward-oriented, self-intersection-free triangle meshes. Throws InputError if an operand
/// is not such a mesh or the result cannot be represented (e.g. non-manifold contact).
void cgal_boolean(const Eigen::MatrixX3d& vertices_a, const Eigen::MatrixX3i& faces_a,
                  const Eigen::MatrixX3d& vertices_b, const Eigen::MatrixX3i& faces_b,
                  BooleanOperation operation, Eigen::MatrixX3d& vertices,
                  Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry::detail
