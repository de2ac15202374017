#pragma once
// VTK XML ImageData (.vti) output, readable by ParaView and VTK: a regular grid of cells with
// named scalar or vector fields on its points or cells, stored as Float32 in a raw appended
// block (vtk_xml_file.hpp), written atomically (atomic_file.hpp). Float32 keeps 7 significant
// digits, below the discretisation error of the grid solutions written here (the voxel
// solver's 1 %, the treecode's 1e−6), at half the size of Float64: 4 bytes per value.
//
//   grid:  cells (nx, ny, nz) — nz = 0 for a 2-D image —, origin and spacing [model units]
//   field: values #items×components, items x fastest (then y, z); #items = Π cells for cell
//          data, Π (cells + 1) for point data; components 1 (scalar) or 3 (vector; 2-D
//          vectors are padded with a zero z component, as VTK expects)

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::output {

struct ImageGrid {
  std::array<long long, 3> cells{0, 0, 0};
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
};

struct ImageField {
  enum class Location { point, cell };
  std::string name;
  Location location = Location::cell;
  const Eigen::MatrixXd* values = nullptr;  ///< #items×components, not owned
};

/// Writes the grid and fields; throws InputError on an I/O error and InternalError if a
/// field's row count does not match its location.
void write_vti(const std::filesystem::path& path, const ImageGrid& grid,
               const std::vector<ImageField>& fields);

}  // namespace bemshape::output
