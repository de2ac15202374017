#include "apps/output/vti_writer.hpp"

#include <bit>
#include <cstdint>
#include <sstream>

#include "apps/output/atomic_file.hpp"
#include "core/errors.hpp"

namespace bemshape::output {

static_assert(std::endian::native == std::endian::little,
              "the VTI files declare byte_order=LittleEndian and are written from memory");

void write_vti(const std::filesystem::path& path, const ImageGrid& grid,
               const std::vector<ImageField>& fields) {
  const bool flat = grid.cells[2] == 0;
  long long cells = 1, points = 1;
  for (int d = 0; d < 3; ++d) {
    if (d == 2 && flat)
      continue;
    cells *= grid.cells[d];
    points *= grid.cells[d] + 1;
  }
  std::ostringstream xml;
  xml.precision(17);
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
  const std::string extent = "0 " + std::to_string(grid.cells[0]) + " 0 " +
                             std::to_string(grid.cells[1]) + " 0 " + std::to_string(grid.cells[2]);
  xml << "  <ImageData WholeExtent=\"" << extent << "\" Origin=\"" << grid.origin[0] << ' '
      << grid.origin[1] << ' ' << grid.origin[2] << "\" Spacing=\"" << grid.spacing[0] << ' '
      << grid.spacing[1] << ' ' << grid.spacing[2] << "\">\n";
  xml << "    <Piece Extent=\"" << extent << "\">\n";
  std::uint64_t offset = 0;
  std::vector<int> output_components(fields.size());
  for (auto location : {ImageField::Location::point, ImageField::Location::cell}) {
    const char* tag = location == ImageField::Location::point ? "PointData" : "CellData";
    xml << "      <" << tag << ">\n";
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const auto& field = fields[f];
      if (field.location != location)
        continue;
      const long long expected = location == ImageField::Location::point ? points : cells;
      if (field.values == nullptr || field.values->rows() != expected)
        throw InternalError("write_vti: field '" + field.name + "' has " +
                            std::to_string(field.values ? field.values->rows() : 0) +
                            " rows, expected " + std::to_string(expected));
      const int components = static_cast<int>(field.values->cols());
      output_components[f] = components == 1 ? 1 : 3;
      xml << "        <DataArray type=\"Float32\" Name=\"" << field.name
          << "\" NumberOfComponents=\"" << output_components[f]
          << "\" format=\"appended\" offset=\"" << offset << "\"/>\n";
      offset += sizeof(std::uint64_t) +
                static_cast<std::uint64_t>(expected) * output_components[f] * sizeof(float);
    }
    xml << "      </" << tag << ">\n";
  }
  xml << "    </Piece>\n  </ImageData>\n  <AppendedData encoding=\"raw\">\n_";

  AtomicFileWriter writer(path);
  writer.write(xml.str());
  std::vector<float> buffer;
  for (auto location : {ImageField::Location::point, ImageField::Location::cell}) {
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const auto& field = fields[f];
      if (field.location != location)
        continue;
      const Eigen::MatrixXd& v = *field.values;
      const int components = output_components[f];
      buffer.assign(static_cast<std::size_t>(v.rows()) * components, 0.0f);
      for (Eigen::Index i = 0; i < v.rows(); ++i)
        for (Eigen::Index c = 0; c < std::min<Eigen::Index>(v.cols(), components); ++c)
          buffer[static_cast<std::size_t>(i * components + c)] = static_cast<float>(v(i, c));
      const std::uint64_t bytes = buffer.size() * sizeof(float);
      writer.write(&bytes, sizeof bytes);
      writer.write(buffer.data(), bytes);
    }
  }
  writer.write("\n  </AppendedData>\n</VTKFile>\n");
  writer.commit();
}

}  // namespace bemshape::output
