#pragma once
// VTK XML PolyData (.vtp), readable by ParaView and VTK: a triangle surface with named
// scalar or vector fields on its points and cells. Points and fields are Float64, so values
// read back are exactly those computed; the triangles are the Int64 arrays connectivity (3
// vertex indices per face, counter-clockwise seen from outside) and offsets (3, 6, …, 3·#F).
// Binary by default: raw appended data, about 8·(3·#V + 4·#F) bytes plus 8 bytes per field
// value (vtk_xml_file.hpp). Written atomically (atomic_file.hpp).
//
//   vertices: #V×3 [model units]
//   faces:    #F×3 vertex indices
//   point field values: #V×components, cell field values: #F×components (1 or 3)

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "apps/output/vtk_xml_file.hpp"

namespace bemshape::output {

struct MeshField {
  std::string name;
  const Eigen::MatrixXd* values = nullptr;  ///< #items×components, not owned
};

/// Writes the surface and its fields; throws InputError on an I/O error and InternalError if
/// a field's row count does not match the vertex or face count.
void write_vtp(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixX3i& faces, const std::vector<MeshField>& point_fields,
               const std::vector<MeshField>& cell_fields,
               VtkEncoding encoding = VtkEncoding::binary);

}  // namespace bemshape::output
