// The result writers of apps/output (CSV, VTP, PLY, STL, and the VTI writer as the features
// command uses it): every file is parsed back by the independent readers of
// file_readers.hpp, which check that it is well-formed, and the numbers read back must equal
// the numbers written (exactly for the text formats and Float64 arrays, to float32 rounding
// for the float32 ones). test_vtk_readers.py reads the same writers' files with VTK.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>

#include "apps/output/colour_map.hpp"
#include "apps/output/csv_writer.hpp"
#include "apps/output/ply_writer.hpp"
#include "apps/output/stl_writer.hpp"
#include "apps/output/vti_writer.hpp"
#include "apps/output/vtp_writer.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"
#include "tests/apps/output/file_readers.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

/// Values that stress a text format: tiny, huge, negative, many digits, integers, zero.
Eigen::MatrixXd awkward_values(Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < cols; ++c)
      m(r, c) = std::pow(-1.0, double(r + c)) * std::pow(10.0, double((r * 7 + c * 3) % 40 - 20)) /
                3.0 * double(r + 1);
  m(0, 0) = 0.0;
  m(rows - 1, cols - 1) = 1e6;
  return m;
}

}  // namespace

TEST_CASE("CSV: exact header, one row per item, numbers read back bit-identical") {
  const Eigen::MatrixXd rows = awkward_values(17, 4);
  const std::string path = scratch("writers.csv");
  output::write_csv(path, {"x", "y", "z", "thickness"}, rows);
  const std::string text = slurp(path);
  CHECK(text.substr(0, text.find('\n')) == "x,y,z,thickness");
  const CsvTable table = parse_csv(text);
  REQUIRE(table.rows.rows() == 17);
  CHECK(table.rows == rows);
  CHECK_THROWS_AS(output::format_csv({"x"}, rows), InternalError);
}

TEST_CASE("VTP binary and ASCII: balanced XML, array lengths match the mesh, values exact") {
  const geometry::SurfaceMesh mesh =
      geometry::make_box(Eigen::Vector3d(-1, -2, -0.5), Eigen::Vector3d(1.5, 2, 0.25), 0.7);
  const Eigen::MatrixXd point_scalar = awkward_values(mesh.num_vertices(), 1);
  const Eigen::MatrixXd point_vector = awkward_values(mesh.num_vertices(), 3);
  const Eigen::MatrixXd cell_scalar = awkward_values(mesh.num_faces(), 1);
  for (const auto encoding : {output::VtkEncoding::binary, output::VtkEncoding::ascii}) {
    const bool binary = encoding == output::VtkEncoding::binary;
    CAPTURE(binary);
    const std::string path = scratch(binary ? "writers.vtp" : "writers_ascii.vtp");
    output::write_vtp(path, mesh.vertices(), mesh.faces(),
                      {{"thickness", &point_scalar}, {"n_f", &point_vector}},
                      {{"thickness", &cell_scalar}}, encoding);
    const std::string text = slurp(path);
    CHECK((text.find("<AppendedData encoding=\"raw\">") != std::string::npos) == binary);
    const VtpFile vtp = parse_vtp(text);
    CHECK(vtp.points == mesh.num_vertices());
    CHECK(vtp.polys == mesh.num_faces());
    CHECK(vtp.coordinates == mesh.vertices());
    CHECK(vtp.connectivity == mesh.faces().cast<double>());
    CHECK(vtp.point_data.at("thickness") == point_scalar);
    CHECK(vtp.point_data.at("n_f") == point_vector);
    CHECK(vtp.cell_data.at("thickness") == cell_scalar);
    if (binary) {  // 8 bytes a value, 8 for each array's byte count, and under 2 kB of XML
      const auto nv = static_cast<std::size_t>(mesh.num_vertices()),
                 nf = static_cast<std::size_t>(mesh.num_faces());
      const std::size_t payload = 8 * (3 * nv + 4 * nf + (1 + 3) * nv + nf) + 8 * 6;
      CHECK(text.size() > payload);
      CHECK(text.size() < payload + 2000);
    }
  }

  const Eigen::MatrixXd wrong = Eigen::MatrixXd::Zero(3, 1);
  CHECK_THROWS_AS(
      output::write_vtp(scratch("bad.vtp"), mesh.vertices(), mesh.faces(), {{"w", &wrong}}, {}),
      InternalError);
  CHECK_FALSE(fs::exists(scratch("bad.vtp")));  // nothing half-written
}

TEST_CASE("VTP ASCII: indices and offsets above 10⁵ are written as integers") {
  // The shortest double form of 100000 is "1e+05", which VTK reads as 1: every index and
  // offset from 10⁵ on must come out in integer digits.
  const Eigen::Index nf = 40000;  // vertex indices up to 119999, offsets up to 120000
  Eigen::MatrixX3d vertices = Eigen::MatrixX3d::Zero(3 * nf, 3);
  vertices.col(0).setLinSpaced(0.0, 1.0);
  Eigen::MatrixX3i faces(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f)
    faces.row(f) << int(3 * f), int(3 * f + 1), int(3 * f + 2);
  const std::string path = scratch("writers_integers.vtp");
  output::write_vtp(path, vertices, faces, {}, {}, output::VtkEncoding::ascii);
  const std::string text = slurp(path);
  CHECK(text.find("e+") == std::string::npos);
  CHECK(text.find(" 119999\n") != std::string::npos);
  CHECK(text.find(" 120000\n") != std::string::npos);
  const VtpFile vtp = parse_vtp(text);  // REQUIREs integer tokens in the Int64 arrays
  CHECK(vtp.connectivity == faces.cast<double>());
}

TEST_CASE("PLY: header and payload size by the format, floats, colours and faces read back") {
  const geometry::SurfaceMesh mesh = geometry::make_geodesic_sphere(2.0, 3);
  Eigen::VectorXd field = mesh.vertices().col(2);  // −2 … 2
  const std::string path = scratch("writers.ply");
  output::PlyColouring colouring;
  colouring.colour_minimum = -1.0;
  colouring.colour_maximum = 1.0;
  colouring.comment = "test";
  output::write_ply(path, mesh.vertices(), mesh.faces(), field, colouring);
  const PlyFile ply = parse_ply(slurp(path), "thickness");  // with "quality" equal to it
  REQUIRE(ply.vertices.rows() == mesh.num_vertices());
  CHECK(ply.vertices == mesh.vertices().cast<float>());
  CHECK(ply.field == field.cast<float>());
  CHECK(ply.faces == mesh.faces());
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    // Values outside the colour range are clamped to its ends.
    const output::Rgb expected = output::viridis((field(v) + 1.0) / 2.0);
    CHECK(ply.colours(v, 0) == expected.r);
    CHECK(ply.colours(v, 1) == expected.g);
    CHECK(ply.colours(v, 2) == expected.b);
  }
  Eigen::Index lowest = 0, highest = 0;
  field.minCoeff(&lowest);
  field.maxCoeff(&highest);
  CHECK(ply.colours(lowest, 0) == output::viridis(0.0).r);
  CHECK(ply.colours(highest, 1) == output::viridis(1.0).g);

  colouring.field_name = "quality";  // the name of the copy for MeshLab
  CHECK_THROWS_AS(
      output::write_ply(scratch("bad.ply"), mesh.vertices(), mesh.faces(), field, colouring),
      InternalError);
}

TEST_CASE("STL: 84 + 50·F bytes, corners and right-hand normals as float32") {
  const geometry::SurfaceMesh mesh =
      geometry::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3), 1.0);
  const std::string path = scratch("writers.stl");
  output::write_binary_stl(path, mesh.vertices(), mesh.faces());
  const std::string bytes = slurp(path);
  REQUIRE(bytes.size() == 84 + 50 * static_cast<std::size_t>(mesh.num_faces()));
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  CHECK(count == mesh.num_faces());
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    float record[12];
    std::memcpy(record, bytes.data() + 84 + 50 * f, sizeof record);
    for (int k = 0; k < 3; ++k) {
      CHECK(record[k] == Approx(mesh.face_normals()(f, k)).margin(1e-7));
      for (int c = 0; c < 3; ++c)
        CHECK(record[3 + 3 * c + k] == static_cast<float>(mesh.corner(f, c)(k)));
    }
  }
}

TEST_CASE("VTI point data as the features command writes it: Float32 blocks of the right size") {
  output::ImageGrid grid;
  grid.cells = {3, 4, 5};
  grid.origin = {-1.0, 0.5, 2.0};
  grid.spacing = {0.25, 0.25, 0.25};
  const Eigen::Index points = 4 * 5 * 6;
  const Eigen::MatrixXd inside = (awkward_values(points, 1).array() > 0).cast<double>();
  const Eigen::MatrixXd s = awkward_values(points, 3) * 1e-3;
  const std::string path = scratch("writers.vti");
  using Location = output::ImageField::Location;
  output::write_vti(path, grid, {{"inside", Location::point, &inside}, {"s", Location::point, &s}});
  const VtiFile vti = parse_vti(slurp(path));
  CHECK(vti.extent == std::array<long long, 6>{0, 3, 0, 4, 0, 5});
  CHECK(vti.origin == Eigen::Vector3d(-1.0, 0.5, 2.0));
  CHECK(vti.spacing == Eigen::Vector3d::Constant(0.25));
  CHECK(vti.point_data.at("inside") == inside.cast<float>());
  CHECK(vti.point_data.at("s") == s.cast<float>());
}
