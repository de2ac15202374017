#pragma once
// Binary little-endian PLY of a triangle surface coloured by a scalar field, for mesh viewers
// that show vertex colours (MeshLab, Blender, CloudCompare):
//
//   element vertex #V: float x, y, z [model units]; float <field name> (e.g. thickness);
//                      float quality (the same values again); uchar red, green, blue
//                      (viridis, colour_map.hpp, of the field between colour_minimum and
//                      colour_maximum, clamped)
//                      uchar defect (only when PlyColouring::defect is given: 1 for a vertex
//                      near a region where the surface crosses itself, coloured kDefectColour)
//   element face #F:   list uchar int vertex_indices (counter-clockwise seen from outside)
//
// "quality" is the vertex property MeshLab (vcglib's PLY importer) loads as vertex quality,
// which its Colorize by vertex Quality filter, quality histogram and selection by quality
// work on; other programs see the named field.
//
// Payload size: #V·23 (24 with defect) + #F·13 bytes after "end_header\n". Written atomically.

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::output {

struct PlyColouring {
  std::string field_name = "thickness";
  double colour_minimum = 0.0;  ///< maps to the darkest colour
  double colour_maximum = 1.0;  ///< maps to the brightest colour
  std::string comment;          ///< one header comment line (e.g. the units), may be empty
  /// #V flags, or empty: vertices near a defect region (drawn kDefectColour, property defect).
  std::vector<char> defect;
};

/// vertices: #V×3, faces: #F×3, field: #V. Throws InputError on an I/O error and
/// InternalError if the field's size does not match the vertex count.
void write_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixX3i& faces, const Eigen::Ref<const Eigen::VectorXd>& field,
               const PlyColouring& colouring);

}  // namespace bemshape::output
