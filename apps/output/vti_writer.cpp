#include "apps/output/vti_writer.hpp"

#include "apps/output/number_text.hpp"
#include "apps/output/vtk_xml_file.hpp"
#include "core/errors.hpp"

namespace bemshape::output {

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
  const auto triple = [](const std::array<double, 3>& v) {
    std::string text;
    for (int d = 0; d < 3; ++d) {
      if (d > 0)
        text += ' ';
      append_number(text, v[static_cast<std::size_t>(d)]);
    }
    return text;
  };
  const std::string extent = "0 " + std::to_string(grid.cells[0]) + " 0 " +
                             std::to_string(grid.cells[1]) + " 0 " + std::to_string(grid.cells[2]);
  VtkXmlFile file("ImageData", VtkEncoding::binary);
  file.markup("  <ImageData WholeExtent=\"" + extent + "\" Origin=\"" + triple(grid.origin) +
              "\" Spacing=\"" + triple(grid.spacing) + "\">\n    <Piece Extent=\"" + extent +
              "\">\n");
  for (auto location : {ImageField::Location::point, ImageField::Location::cell}) {
    const std::string tag = location == ImageField::Location::point ? "PointData" : "CellData";
    file.markup("      <" + tag + ">\n");
    for (const ImageField& field : fields) {
      if (field.location != location)
        continue;
      const long long expected = location == ImageField::Location::point ? points : cells;
      if (field.values == nullptr || field.values->rows() != expected)
        throw InternalError("write_vti: field '" + field.name + "' has " +
                            std::to_string(field.values ? field.values->rows() : 0) +
                            " rows, expected " + std::to_string(expected));
      file.data_array(vtk_array(field.name, VtkScalarType::float32, *field.values,
                                field.values->cols() == 1 ? 1 : 3),
                      8);
    }
    file.markup("      </" + tag + ">\n");
  }
  file.markup("    </Piece>\n  </ImageData>\n");
  file.write(path);
}

}  // namespace bemshape::output
