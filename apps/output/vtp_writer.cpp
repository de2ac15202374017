#include "apps/output/vtp_writer.hpp"

#include "core/errors.hpp"

namespace bemshape::output {
namespace {

void append_fields(VtkXmlFile& file, const char* tag, const std::vector<MeshField>& fields,
                   Eigen::Index rows) {
  file.markup(std::string("      <") + tag + ">\n");
  for (const MeshField& field : fields) {
    if (field.values == nullptr || field.values->rows() != rows)
      throw InternalError("write_vtp: field '" + field.name + "' has " +
                          std::to_string(field.values ? field.values->rows() : 0) +
                          " rows, expected " + std::to_string(rows));
    file.data_array(vtk_array(field.name, VtkScalarType::float64, *field.values,
                              static_cast<int>(field.values->cols())),
                    8);
  }
  file.markup(std::string("      </") + tag + ">\n");
}

}  // namespace

void write_vtp(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixX3i& faces, const std::vector<MeshField>& point_fields,
               const std::vector<MeshField>& cell_fields, VtkEncoding encoding) {
  const Eigen::Index nv = vertices.rows(), nf = faces.rows();
  VtkXmlFile file("PolyData", encoding);
  file.markup("  <PolyData>\n    <Piece NumberOfPoints=\"" + std::to_string(nv) +
              "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
              std::to_string(nf) + "\">\n");
  append_fields(file, "PointData", point_fields, nv);
  append_fields(file, "CellData", cell_fields, nf);
  file.markup("      <Points>\n");
  file.data_array({"", VtkScalarType::float64, nv, 3,
                   [&vertices](Eigen::Index v, int c) { return vertices(v, c); }},
                  8);
  file.markup("      </Points>\n      <Polys>\n");
  // One component each: VTK refuses a connectivity array of 3-component tuples.
  file.data_array({"connectivity", VtkScalarType::int64, 3 * nf, 1,
                   [&faces](Eigen::Index i, int) { return double(faces(i / 3, i % 3)); }},
                  8);
  file.data_array({"offsets", VtkScalarType::int64, nf, 1,
                   [](Eigen::Index f, int) { return double(3 * (f + 1)); }},
                  8);
  file.markup("      </Polys>\n    </Piece>\n  </PolyData>\n");
  file.write(path);
}

}  // namespace bemshape::output
