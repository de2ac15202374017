#pragma once
// A VTK XML file (VTK's "XML file formats": .vtp, .vti, …) being composed: the caller adds the
// dataset's markup and its DataArrays in document order, and write() stores the file
// atomically (atomic_file.hpp).
//
// Encodings of the arrays:
//   binary (default): every DataArray says format="appended" and the byte offset of its
//     array in the raw appended block that follows the dataset,
//       <AppendedData encoding="raw">_[UInt64 byte count][values]…[UInt64 byte count][values]
//     (header_type="UInt64", byte_order="LittleEndian", values tuple after tuple, the
//     components of a tuple together). VTK reads it as it is stored, with no parsing.
//   ascii: the values as text inside each DataArray, integers in decimal, floating-point
//     values in their shortest round-trip form (number_text.hpp), so they read back exactly.
// Either way integer arrays carry integers (an Int64 array never holds "1e+05", which VTK
// reads as 1) and Float64 arrays every bit of the double.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bemshape::output {

enum class VtkEncoding { binary, ascii };

/// The VTK scalar types bemshape writes: Int64 (connectivity, offsets), Float32, Float64.
enum class VtkScalarType { int64, float32, float64 };

/// One DataArray: `tuples` × `components` numbers, value(tuple, component) each (converted to
/// `type`; Int64 values must be integers below 2⁵³ in magnitude).
struct VtkDataArray {
  std::string name;  ///< the Name attribute; empty for the Points array, which has none
  VtkScalarType type = VtkScalarType::float64;
  Eigen::Index tuples = 0;
  int components = 1;
  std::function<double(Eigen::Index tuple, int component)> value;
};

/// The array of an Eigen matrix's rows (#tuples × components; not copied, must outlive
/// write()); `components` larger than the matrix's columns pads the tuples with zeros (VTK
/// expects 3-component vectors, so 2-D vectors get a zero z).
VtkDataArray vtk_array(std::string name, VtkScalarType type, const Eigen::MatrixXd& values,
                       int components);

class VtkXmlFile {
 public:
  /// Starts `<VTKFile type="dataset_type" …>`; `dataset_type` is the VTK dataset element
  /// ("PolyData", "ImageData").
  VtkXmlFile(const std::string& dataset_type, VtkEncoding encoding);

  /// Appends markup (start and end tags, attributes) as it is.
  void markup(const std::string& text) { xml_ += text; }
  /// Appends the DataArray element of `array`, indented by `indent` spaces.
  void data_array(VtkDataArray array, int indent);

  /// Closes the file and writes it to `path` atomically; throws InputError on an I/O error.
  /// The arrays' value functions are called here.
  void write(const std::filesystem::path& path);

 private:
  VtkEncoding encoding_;
  std::string xml_;
  std::vector<VtkDataArray> appended_;  ///< binary: the arrays of the appended block, in order
  std::uint64_t appended_bytes_ = 0;    ///< binary: the block's size so far
};

}  // namespace bemshape::output
