#pragma once
// Binary STL of a triangle surface: 80-byte header, uint32 triangle count, then per triangle
// the unit normal (right-hand rule of the corner order) and three corners as float32, and a
// zero uint16 attribute — 84 + 50·#F bytes, little-endian. Used to hand generated solids
// (tests, benchmarks) to the bemshape program. Written atomically.

#include <filesystem>

#include <Eigen/Core>

namespace bemshape::output {

/// vertices: #V×3 [model units], faces: #F×3, counter-clockwise seen from outside.
void write_binary_stl(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
                      const Eigen::MatrixX3i& faces);

}  // namespace bemshape::output
