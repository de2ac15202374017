#pragma once
// The faces' adjacency through edges: the dual graph of a triangle mesh, used to spread
// values over a surface and to find its edge-connected regions.

#include <Eigen/Core>
#include <vector>

namespace bemshape::geometry {

/// neighbours[f]: the faces other than f that have an edge of f as one of theirs, each
/// once, in increasing order. Three per face on a closed manifold mesh; more across a
/// non-manifold edge, fewer at a border. O(F log F).
std::vector<std::vector<int>> edge_neighbours(const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
