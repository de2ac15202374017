#pragma once
// Internal: the 3MF reader behind read_triangle_soup (mesh_io.hpp). lib3mf (1.x, its plain
// C interface lib3mf_*) is compiled into 3mf_reader.cpp only and never appears in a header.
//
// A 3MF file (3D Manufacturing Format core specification 1.2) is a ZIP package whose model
// part lists resources (objects: a mesh, or components that place other objects with an
// affine transform) and a build (items that place objects in the build volume, each with an
// optional transform). The part is the union of what the build items place; every placed
// mesh is copied into the soup with its composed transform applied,
//
//   x_build = T_item · T_component_1 · … · T_component_k · x_object,
//
// each T an affine map x ↦ R x + t written in the file as the 12 numbers "m00 m01 m02 m10
// m11 m12 m20 m21 m22 m30 m31 m32" (row-vector convention of the specification; lib3mf
// hands them over as the 3×4 matrix [R | t] for column vectors). A transform with
// det R < 0 mirrors the mesh, so the corner order of its triangles is reversed to keep the
// file's orientation.

#include <filesystem>
#include <string_view>

#include "geometry/mesh_io.hpp"

namespace bemshape::geometry::detail {

/// Millimetres per 3MF unit: micron 1e-3, millimeter 1, centimeter 10, inch 25.4, foot 304.8,
/// meter 1000 (the six values of the `unit` attribute; the default is millimeter).
double millimetres_per_3mf_unit(std::string_view unit);

/// Reads the 3MF package `bytes` (the contents of `path`, which names it in messages) into
/// `soup`: vertices, faces, format "3MF", unit, millimetres_per_unit, build_items,
/// mesh_instances, corners_in_file and the notes on skipped objects. Only objects of type
/// "model" are part of the solid; objects of type "support", "solidsupport", "surface" and
/// "other" are skipped with a note.
///
/// Throws InputError naming the file, the build item (counted from 1), the object id and
/// what is wrong: not a readable 3MF package (lib3mf's message), no build items, a transform
/// that is not finite or is singular, components nested deeper than kMax3mfComponentDepth
/// (a cycle), a mesh object without triangles or with a beam lattice, a triangle referring
/// to a missing vertex, a non-finite coordinate.
void read_3mf(const std::filesystem::path& path, std::string_view bytes, TriangleSoup& soup);

/// Components placing components deeper than this are refused: the specification forbids
/// cycles, and no real assembly nests 64 levels, so a deeper chain is a corrupt file.
inline constexpr int kMax3mfComponentDepth = 64;

}  // namespace bemshape::geometry::detail
