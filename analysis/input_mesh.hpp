#pragma once
// The input of every job as a mesh in memory: a triangle soup from another program (e.g.
// numpy arrays) welded, validated, repaired and oriented exactly as a mesh file is
// (geometry/mesh_preparation.hpp), so that measure_thickness and its siblings give the same
// results for the same triangles whichever way they come.

#include <string>

#include <Eigen/Core>

#include "core/progress.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::analysis {

/// The triangles F over the vertices V welded, validated and repaired as far as is safe, with
/// the report of every problem and repair (geometry::inspect_triangle_soup): what `bemshape
/// check` gives for a file. Does not throw for mesh defects (check report.usable()); throws
/// InputError for indices out of range and non-finite positions. V and F as below.
geometry::PreparedMesh inspect_triangles(const Eigen::Ref<const Eigen::MatrixX3d>& V,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& F,
                                         const std::string& name = "triangles",
                                         const ProgressCallback& progress = {});

/// The prepared mesh of the triangles F over the vertices V:
///   V: #V×3 vertex positions [model units], finite;
///   F: #F×3 vertex indices into V (0-based), each in [0, #V).
/// `name` stands for the mesh in messages and reports (MeshReport::source). Throws
/// InputError for indices out of range, non-finite positions, or a mesh that cannot bound a
/// solid (MeshReport::refusal_message).
geometry::PreparedMesh prepare_triangles(const Eigen::Ref<const Eigen::MatrixX3d>& V,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& F,
                                         const std::string& name = "triangles",
                                         const ProgressCallback& progress = {});

}  // namespace bemshape::analysis
