#include "apps/output/vtp_writer.hpp"

#include "apps/output/atomic_file.hpp"
#include "apps/output/number_text.hpp"
#include "core/errors.hpp"

namespace bemshape::output {
namespace {

/// Six numbers per line keeps the file readable in a text editor.
constexpr Eigen::Index kNumbersPerLine = 6;

void append_array(std::string& xml, const char* type, const std::string& name, Eigen::Index rows,
                  Eigen::Index components, const auto& value) {
  xml += "        <DataArray type=\"";
  xml += type;
  xml += '"';
  if (!name.empty())
    xml += " Name=\"" + name + '"';
  xml += " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">\n";
  Eigen::Index count = 0;
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < components; ++c) {
      xml += count % kNumbersPerLine == 0 ? "          " : " ";
      append_number(xml, value(r, c));
      if (++count % kNumbersPerLine == 0)
        xml += '\n';
    }
  if (count % kNumbersPerLine != 0)
    xml += '\n';
  xml += "        </DataArray>\n";
}

void append_fields(std::string& xml, const char* tag, const std::vector<MeshField>& fields,
                   Eigen::Index rows) {
  xml += "      <";
  xml += tag;
  xml += ">\n";
  for (const MeshField& field : fields) {
    if (field.values == nullptr || field.values->rows() != rows)
      throw InternalError("write_vtp: field '" + field.name + "' has " +
                          std::to_string(field.values ? field.values->rows() : 0) +
                          " rows, expected " + std::to_string(rows));
    const Eigen::MatrixXd& v = *field.values;
    append_array(xml, "Float64", field.name, rows, v.cols(),
                 [&](Eigen::Index r, Eigen::Index c) { return v(r, c); });
  }
  xml += "      </";
  xml += tag;
  xml += ">\n";
}

}  // namespace

void write_vtp(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixX3i& faces, const std::vector<MeshField>& point_fields,
               const std::vector<MeshField>& cell_fields) {
  const Eigen::Index nv = vertices.rows(), nf = faces.rows();
  std::string xml;
  xml.reserve(static_cast<std::size_t>(nv * 60 + nf * 40));
  xml += "<?xml version=\"1.0\"?>\n";
  xml +=
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  xml += "  <PolyData>\n";
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(nv) +
         "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
         std::to_string(nf) + "\">\n";
  append_fields(xml, "PointData", point_fields, nv);
  append_fields(xml, "CellData", cell_fields, nf);
  xml += "      <Points>\n";
  append_array(xml, "Float64", "", nv, 3,
               [&](Eigen::Index r, Eigen::Index c) { return vertices(r, c); });
  xml += "      </Points>\n";
  xml += "      <Polys>\n";
  append_array(xml, "Int64", "connectivity", nf, 3,
               [&](Eigen::Index r, Eigen::Index c) { return double(faces(r, c)); });
  append_array(xml, "Int64", "offsets", nf, 1,
               [&](Eigen::Index r, Eigen::Index) { return double(3 * (r + 1)); });
  xml += "      </Polys>\n";
  xml += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomically(path, xml);
}

}  // namespace bemshape::output
