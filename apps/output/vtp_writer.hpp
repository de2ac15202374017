#pragma once
// VTK XML PolyData (.vtp), readable by ParaView and VTK: a triangle surface with named
// scalar or vector fields on its points and cells. Coordinates and fields are Float64 in
// ASCII, each number in its shortest round-trip form (number_text.hpp), so values read back
// are exactly those written; connectivity and offsets are Int64. Written atomically
// (atomic_file.hpp).
//
//   vertices: #V×3 [model units]
//   faces:    #F×3 vertex indices
//   point field values: #V×components, cell field values: #F×components (1 or 3)

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::output {

struct MeshField {
  std::string name;
  const Eigen::MatrixXd* values = nullptr;  ///< #items×components, not owned
};

/// Writes the surface and its fields; throws InputError on an I/O error and InternalError if
/// a field's row count does not match the vertex or face count.
void write_vtp(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixX3i& faces, const std::vector<MeshField>& point_fields,
               const std::vector<MeshField>& cell_fields);

}  // namespace bemshape::output
