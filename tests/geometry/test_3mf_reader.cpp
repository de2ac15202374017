// The 3MF reader (geometry/detail/3mf_reader.hpp) on files written by lib3mf's own writer
// (model_3mf_writer.hpp): placement by build items and components, units, orientation
// under mirroring, refusals, and agreement with the STL reader on the same part.
#include <unistd.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "geometry/detail/3mf_reader.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/model_3mf_writer.hpp"

using namespace bemshape;
using namespace bemshape::geometry;
using bemshape::testing::Model3mfWriter;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

/// A temporary .3mf path, removed with the object.
struct TempFile {
  std::filesystem::path path;
  explicit TempFile(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("bemshape_test_" + std::to_string(::getpid()) + "_" + name)) {}
  ~TempFile() { std::filesystem::remove(path); }
};

std::string message_of(const std::filesystem::path& path) {
  try {
    read_triangle_soup(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// lib3mf 1.8.1 keeps coordinates and transforms in float32 and writes six decimals: a
// coordinate of magnitude below 100 comes back within 1e-5 (float32 steps are 7.6e-6 at 64).
constexpr double kFloat32Coordinate = 2e-5;

/// Max |a − b| over all entries.
double max_difference(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  REQUIRE(a.rows() == b.rows());
  return (a - b).cwiseAbs().maxCoeff();
}

Eigen::MatrixX3d apply(const Eigen::Affine3d& t, const Eigen::MatrixX3d& v) {
  return (v * t.linear().transpose()).rowwise() + t.translation().transpose();
}

}  // namespace

TEST_CASE("3MF: two build items of one plate, each placed by its transform, unit inch") {
  // Plate 4 x 2 x 0.5: volume 4.
  const SurfaceMesh plate = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 2, 0.5), 1.0);
  const Eigen::Affine3d a = Eigen::Translation3d(10, 0, 0) *
                            Eigen::AngleAxisd(std::numbers::pi / 6, Eigen::Vector3d::UnitZ());
  // The second copy is rotated about x and scaled by 2 (volume x 8).
  const Eigen::Affine3d b = Eigen::Translation3d(0, 20, 5) *
                            Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()) *
                            Eigen::Scaling(2.0);
  Model3mfWriter writer("inch");
  const int object = writer.add_mesh(plate.vertices(), plate.faces(), "model", "plate");
  writer.add_build_item(object, a);
  writer.add_build_item(object, b);
  const TempFile file("two_items.3mf");
  writer.write(file.path);

  const TriangleSoup soup = read_triangle_soup(file.path);
  CHECK(soup.format == "3MF");
  CHECK(soup.unit == "inch");
  CHECK(soup.millimetres_per_unit == 25.4);
  CHECK(soup.build_items == 2);
  CHECK(soup.mesh_instances == 2);
  const Eigen::Index nv = plate.num_vertices(), nf = plate.num_faces();
  REQUIRE(soup.vertices.rows() == 2 * nv);
  REQUIRE(soup.faces.rows() == 2 * nf);
  CHECK(max_difference(soup.vertices.topRows(nv), apply(a, plate.vertices())) <
        kFloat32Coordinate);
  CHECK(max_difference(soup.vertices.bottomRows(nv), apply(b, plate.vertices())) <
        kFloat32Coordinate);
  CHECK(soup.faces.topRows(nf) == plate.faces());
  CHECK(soup.faces.bottomRows(nf) == (plate.faces().array() + static_cast<int>(nv)).matrix());

  const PreparedMesh p = inspect_triangle_soup(soup, file.path.string());
  CHECK(p.report.usable());
  CHECK(p.report.shells == 2);
  CHECK(p.report.unit == "inch");
  CHECK(p.report.converted_from.empty());
  CHECK(p.report.format == "3MF (2 build items, 2 meshes placed)");
  CHECK(p.report.volume == Approx(4.0 * (1 + 8)).epsilon(1e-5));

  MeshPreparationOptions to_mm;
  to_mm.convert_to_millimetres = true;
  const PreparedMesh mm = inspect_triangle_soup(soup, file.path.string(), to_mm);
  CHECK(mm.report.unit == "millimeter");
  CHECK(mm.report.converted_from == "inch");
  CHECK(mm.report.volume == Approx(36.0 * std::pow(25.4, 3)).epsilon(1e-5));
  CHECK(mm.report.bounding_box.diagonal() ==
        Approx(25.4 * p.report.bounding_box.diagonal()).epsilon(1e-12));
  CHECK(mm.report.repairs.back() == "converted the coordinates from inch to millimeter (x 25.4)");
}

TEST_CASE("3MF: components compose their transforms with the build item's") {
  const SurfaceMesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.5);
  const Eigen::Affine3d c1(Eigen::Translation3d(0, 0, 0));
  const Eigen::Affine3d c2 = Eigen::Translation3d(0, 0, 3) *
                             Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitZ());
  const Eigen::Affine3d item = Eigen::Translation3d(5, -2, 1) *
                               Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized());
  Model3mfWriter writer("millimeter");
  const int mesh = writer.add_mesh(cube.vertices(), cube.faces());
  const int assembly = writer.add_components({{mesh, c1}, {mesh, c2}});
  writer.add_build_item(assembly, item);
  const TempFile file("components.3mf");
  writer.write(file.path);

  const TriangleSoup soup = read_triangle_soup(file.path);
  CHECK(soup.build_items == 1);
  CHECK(soup.mesh_instances == 2);
  CHECK(soup.unit == "millimeter");
  const Eigen::Index nv = cube.num_vertices();
  REQUIRE(soup.vertices.rows() == 2 * nv);
  CHECK(max_difference(soup.vertices.topRows(nv), apply(item * c1, cube.vertices())) <
        kFloat32Coordinate);
  CHECK(max_difference(soup.vertices.bottomRows(nv), apply(item * c2, cube.vertices())) <
        kFloat32Coordinate);
  const PreparedMesh p = inspect_triangle_soup(soup, "components");
  CHECK(p.report.usable());
  CHECK(p.report.shells == 2);
  CHECK(p.report.volume == Approx(2.0).epsilon(1e-5));
}

TEST_CASE("3MF: a mirroring transform keeps the file's orientation") {
  const SurfaceMesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3), 1.0);
  Model3mfWriter writer;
  const int mesh = writer.add_mesh(cube.vertices(), cube.faces());
  writer.add_build_item(mesh, Eigen::Affine3d(Eigen::Scaling(-1.0, 1.0, 1.0)));
  const TempFile file("mirror.3mf");
  writer.write(file.path);
  const PreparedMesh p = inspect_triangle_soup(read_triangle_soup(file.path), "mirror");
  CHECK(p.report.usable());
  CHECK(p.report.volume == Approx(6.0).epsilon(1e-6));
  CHECK(p.report.bounding_box.min.x() == Approx(-1.0));
  for (const MeshProblem& problem : p.report.problems)
    CHECK(problem.what.find("inside out") == std::string::npos);
}

TEST_CASE("3MF: every unit of the specification, and objects that are not part of the solid") {
  for (const auto& [unit, mm] : {std::pair<std::string, double>{"micron", 1e-3},
                                 {"millimeter", 1.0},
                                 {"centimeter", 10.0},
                                 {"inch", 25.4},
                                 {"foot", 304.8},
                                 {"meter", 1000.0}}) {
    CAPTURE(unit);
    CHECK(detail::millimetres_per_3mf_unit(unit) == mm);
    const SurfaceMesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1.0);
    Model3mfWriter writer(unit);
    writer.add_build_item(writer.add_mesh(cube.vertices(), cube.faces()));
    const int support = writer.add_mesh(cube.vertices(), cube.faces(), "support", "tower");
    writer.add_build_item(support, Eigen::Affine3d(Eigen::Translation3d(3, 0, 0)));
    const TempFile file("unit.3mf");
    writer.write(file.path);
    const TriangleSoup soup = read_triangle_soup(file.path);
    CHECK(soup.unit == unit);
    CHECK(soup.millimetres_per_unit == mm);
    CHECK(soup.build_items == 2);
    CHECK(soup.mesh_instances == 1);  // the support is skipped
    REQUIRE(soup.notes.size() == 1);
    CHECK_THAT(soup.notes[0],
               Catch::Contains("build item 2, object id " +
                               std::to_string(writer.object_id(support)) +
                               " ('tower') is of type \"support\", not \"model\": skipped"));
    MeshPreparationOptions to_mm;
    to_mm.convert_to_millimetres = true;
    const PreparedMesh p = inspect_triangle_soup(soup, "unit", to_mm);
    CHECK(p.report.volume == Approx(mm * mm * mm).epsilon(1e-6));
    CHECK(p.report.unit == "millimeter");
  }
}

TEST_CASE("3MF: a package written without lib3mf (scripts/make_bad_corpus, zipfile)") {
  // The unit cube in centimetres, moved by (1, 0, 0) by the transform of its build item.
  const TriangleSoup soup = read_triangle_soup(data + "/formats/cube_cm_shifted.3mf");
  CHECK(soup.faces.rows() == 12);
  CHECK(soup.unit == "centimeter");
  CHECK(soup.vertices.col(0).minCoeff() == 1.0);
  CHECK(soup.vertices.col(0).maxCoeff() == 2.0);
  CHECK(soup.vertices.rightCols<2>().minCoeff() == 0.0);
  CHECK(soup.vertices.rightCols<2>().maxCoeff() == 1.0);
  MeshPreparationOptions to_mm;
  to_mm.convert_to_millimetres = true;
  const PreparedMesh p = inspect_triangle_soup(soup, "cube_cm_shifted.3mf", to_mm);
  CHECK(p.report.usable());
  CHECK(p.report.volume == Approx(1000.0).epsilon(1e-12));
  CHECK(p.report.bounding_box.min.x() == Approx(10.0).epsilon(1e-12));
  CHECK_THAT(message_of(data + "/bad/bad_index.3mf"),
             Catch::Contains("cannot be read as a 3MF package: Invalid model node index"));
}

TEST_CASE("3MF: refusals say what and where") {
  const SurfaceMesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1.0);
  {
    const TempFile file("not_a_zip.3mf");
    std::ofstream(file.path) << "solid cube\nendsolid cube\n";
    CHECK_THAT(message_of(file.path),
               Catch::StartsWith(file.path.string() + ": cannot be read as a 3MF package: "));
  }
  {
    Model3mfWriter writer;
    writer.add_mesh(cube.vertices(), cube.faces());
    const TempFile file("no_build.3mf");
    writer.write(file.path);
    CHECK_THAT(message_of(file.path), Catch::Contains("the 3MF build has no items"));
  }
  {
    Model3mfWriter writer;
    writer.add_build_item(writer.add_mesh(cube.vertices(), cube.faces(), "support"));
    const TempFile file("only_support.3mf");
    writer.write(file.path);
    CHECK_THAT(message_of(file.path), Catch::Contains("places no object of type \"model\""));
  }
  {
    Model3mfWriter writer;
    const int mesh = writer.add_mesh(cube.vertices(), cube.faces());
    writer.add_build_item(mesh);
    writer.add_build_item(mesh, Eigen::Affine3d(Eigen::Scaling(1.0, 0.0, 1.0)));
    const TempFile file("singular.3mf");
    writer.write(file.path);
    CHECK_THAT(message_of(file.path),
               Catch::Contains(": build item 2: the transform is singular (determinant 0"));
  }
  {
    Model3mfWriter writer;
    const int mesh = writer.add_mesh(cube.vertices(), cube.faces(), "model", "lattice");
    writer.add_beam(mesh);
    writer.add_build_item(mesh);
    const TempFile file("beams.3mf");
    writer.write(file.path);
    CHECK_THAT(message_of(file.path),
               Catch::Contains("build item 1, object id " + std::to_string(writer.object_id(mesh)) +
                               " ('lattice'): has a beam lattice (1 beam)"));
  }
}

TEST_CASE("3MF and STL of the same part give the same mesh") {
  // plate_holes (a usable part in mm) through the whole preparation, and box.STL (ten
  // overlapping parts) as read: the 3MF written from the STL soup reads back the same
  // triangles at the same positions, to 1e-6 of the bounding-box diagonal. STL coordinates
  // are float32 and lib3mf's writer prints them exactly enough, but lib3mf 1.8.1's XML
  // number parser rounds about 5 % of them one float32 step (6e-8 relative) away from the
  // nearest: 3e-5 mm at 300 mm.
  constexpr double kSameGeometry = 1e-6;
  for (const char* name : {"plate_holes.STL", "box.STL"}) {
    CAPTURE(name);
    const TriangleSoup stl = read_triangle_soup(data + "/meshes/" + name);
    Model3mfWriter writer("millimeter");
    writer.add_build_item(writer.add_mesh(stl.vertices, stl.faces));
    const TempFile file(std::string(name) + ".3mf");
    writer.write(file.path);
    const TriangleSoup threemf = read_triangle_soup(file.path);
    const double diagonal =
        (stl.vertices.colwise().maxCoeff() - stl.vertices.colwise().minCoeff()).norm();
    REQUIRE(threemf.faces.rows() == stl.faces.rows());
    CHECK(threemf.faces == stl.faces);
    CHECK(max_difference(threemf.vertices, stl.vertices) < kSameGeometry * diagonal);
  }
  const PreparedMesh stl = prepare_mesh_file(data + "/meshes/plate_holes.STL");
  const TriangleSoup soup = read_triangle_soup(data + "/meshes/plate_holes.STL");
  Model3mfWriter writer("millimeter");
  writer.add_build_item(writer.add_mesh(soup.vertices, soup.faces));
  const TempFile file("plate_holes.3mf");
  writer.write(file.path);
  const PreparedMesh threemf = prepare_mesh_file(file.path);
  CHECK(threemf.report.unit == "millimeter");
  CHECK(stl.report.unit.empty());
  REQUIRE(threemf.mesh.num_faces() == stl.mesh.num_faces());
  CHECK(threemf.mesh.faces() == stl.mesh.faces());
  CHECK(max_difference(threemf.mesh.vertices(), stl.mesh.vertices()) <
        kSameGeometry * stl.report.bounding_box.diagonal());
  CHECK(threemf.report.volume == Approx(stl.report.volume).epsilon(1e-7));
  CHECK(threemf.report.area == Approx(stl.report.area).epsilon(1e-7));
}
