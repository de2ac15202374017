#pragma once
// bemshape's own readers of the polygon mesh formats OBJ, OFF and PLY (ASCII and binary).
//
// They replaced OpenMesh's readers for these formats, which fuzzing showed to abort on an
// assert (OBJ), crash in the PLY header parser, loop forever on a PLY header without
// `end_header`, take tens of seconds on a 140-byte OFF file, and return vertices and indices
// they never read when an OFF file is shorter than its header says (docs/reliability.md).
// These readers check the whole structure as they go: every count against the data that is
// actually there (nothing is allocated from a header's count), every coordinate finite,
// every face index in range. A failure is an InputError naming the file and the line (or,
// for binary PLY, the byte offset) and what is wrong.
//
// The result is a polygon soup: faces keep their corner count; mesh_io.cpp triangulates.

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

namespace bemshape::geometry::detail {

/// Vertices and polygons as stored in a file.
struct PolygonSoup {
  /// Vertex positions [file units], all finite.
  std::vector<Eigen::Vector3d> points;
  /// Corner vertex indices of every polygon, one polygon after the other, each in
  /// [0, points.size()).
  std::vector<std::size_t> corners;
  /// Polygon k has the corners corners[start[k]] .. corners[start[k + 1] - 1];
  /// start.size() = #polygons + 1. Polygons may have fewer than three corners.
  std::vector<std::size_t> start{0};

  std::size_t num_polygons() const { return start.size() - 1; }
};

/// Wavefront OBJ: `v x y z [w]` vertices and `f` faces whose corners are `v`, `v/vt`,
/// `v//vn` or `v/vt/vn` with v counted from 1 (negative: relative to the vertices read so
/// far). Every other statement (vt, vn, g, o, s, usemtl, mtllib, l, ...) is ignored; `#`
/// starts a comment.
PolygonSoup read_obj(const std::filesystem::path& path, std::string_view text);

/// ASCII OFF (Geomview): a keyword `OFF` with the optional prefixes ST, C, N (texture
/// coordinates, colours, normals per vertex, which are skipped), the counts NV NF [NE], NV
/// vertex lines whose first three numbers are the position, and NF face lines `n i1 .. in
/// [colour]` with indices counted from 0. `#` starts a comment. Binary OFF and the 4-D and
/// n-D variants (4OFF, nOFF) are refused with a message saying so.
PolygonSoup read_off(const std::filesystem::path& path, std::string_view text);

/// PLY (ascii, binary_little_endian, binary_big_endian 1.0): the element `vertex` with the
/// scalar properties x, y, z, and the element `face` with an integer list property
/// `vertex_indices` (or `vertex_index`), indices counted from 0. Other elements and
/// properties are read and skipped.
PolygonSoup read_ply(const std::filesystem::path& path, std::string_view text);

}  // namespace bemshape::geometry::detail
