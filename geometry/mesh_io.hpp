#pragma once
// Reading triangle meshes from STL (ASCII and binary), OBJ, OFF, PLY and 3MF files.
//
// The result is a raw triangle soup rather than a halfedge mesh: a halfedge mesh refuses
// non-manifold faces and would silently drop exactly the defects that mesh validation must
// report. Nothing is welded, validated or repaired here (see vertex_welding.hpp,
// mesh_validation.hpp, mesh_preparation.hpp).
//
// STL goes through OpenMesh's STL reader after bemshape's own checks of the whole file.
// OBJ, OFF and PLY are parsed by bemshape's own readers (detail/polygon_file_readers.hpp):
// fuzzing found OpenMesh's readers of these formats aborting, crashing, hanging or
// returning data they never read on malformed files (docs/reliability.md). 3MF goes through
// lib3mf (detail/3mf_reader.hpp): every build item, with its transform and the transforms
// of the components it places.
//
// Units: coordinates are returned exactly as stored in the file (3MF: after the build's
// transforms). STL, OBJ, OFF and PLY record no length unit, so every bemshape length
// (thickness, edge length, volume) is in the file's units; CAD STL exports are usually
// millimetres. 3MF records its unit (TriangleSoup::unit); converting to millimetres is a
// preparation option (MeshPreparationOptions::convert_to_millimetres), never done here.

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace bemshape::geometry {

/// The triangles of a mesh file as stored, before welding.
struct TriangleSoup {
  /// #V×3 vertex positions [file units].
  Eigen::MatrixX3d vertices;
  /// #F×3 vertex indices, in the file's corner order.
  Eigen::MatrixX3i faces;
  /// "binary STL", "ASCII STL", "OBJ", "OFF", "PLY" or "3MF".
  std::string format;
  /// The length unit the file records: 3MF's `unit` attribute ("micron", "millimeter",
  /// "centimeter", "inch", "foot", "meter"); empty for formats that record none.
  std::string unit;
  /// Millimetres per file unit (1e-3 for micron, ..., 1000 for meter); 0 if `unit` is empty.
  double millimetres_per_unit = 0.0;
  /// 3MF: the build items read, and the meshes they placed (a build item of a components
  /// object places one mesh per mesh object it reaches).
  std::size_t build_items = 0;
  std::size_t mesh_instances = 0;
  /// What the reader left out or noticed without refusing, one sentence each (3MF: objects of
  /// type "support" or "other", which are not part of the solid).
  std::vector<std::string> notes;
  /// Polygons with more than three corners that were split into triangle fans, and the
  /// number of triangles this produced.
  std::size_t polygons_triangulated = 0;
  std::size_t triangles_from_polygons = 0;
  /// Faces with fewer than three distinct corners that the reader dropped (OpenMesh's STL
  /// reader drops facets whose corners coincide exactly; OBJ/OFF/PLY polygons listing fewer
  /// than 3 corners).
  std::size_t collapsed_faces_dropped = 0;
  /// Triangle corners stored in the file (3 per STL facet) and, for STL, how many distinct
  /// positions OpenMesh's STL reader kept after merging exactly equal corners.
  std::size_t corners_in_file = 0;
};

/// Reads `path` by its extension (.stl, .obj, .off, .ply, .3mf; case-insensitive).
///
/// Before any parsing, a binary STL's triangle count is checked against the file size
/// (84 + 50·n bytes), so a small file claiming billions of triangles is rejected without
/// allocating; ASCII STL vertex lines are checked for unparsable and non-finite numbers,
/// which OpenMesh's reader would otherwise read as zeros. OBJ, OFF and PLY readers never
/// allocate from a header's count: a PLY header whose counts need more bytes than the file
/// has is refused before its body is read, and OFF/PLY lists grow only with data present.
///
/// Only regular files are read: the file is opened without blocking and its type checked on
/// the open descriptor, so a FIFO, socket or device given as the input is refused at once
/// (opening a FIFO for reading would wait for a writer forever).
///
/// Throws InputError (one line naming the file, the line, byte offset or 3MF object where it
/// can, and what is wrong) if the path is missing, a directory, a FIFO or another non-regular
/// file, unreadable or empty, the extension is not supported, the file is truncated or
/// malformed, a coordinate is NaN/Inf, a face refers to a missing vertex, or there are no
/// triangles.
TriangleSoup read_triangle_soup(const std::filesystem::path& path);

/// Writes an indexed triangle mesh as binary STL (float32 coordinates, zero normals are
/// recomputed from the corner order). Throws InputError if the file cannot be written.
void write_binary_stl(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
                      const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
