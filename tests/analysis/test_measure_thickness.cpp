// analysis/measure_thickness.hpp on the validation ball (R = 0.5, h0 = 0.3, a = 0.2, the
// default element size: 1280 faces) against its closed form, the same triangles given as a
// file and as arrays giving the same thickness to the last bit, and as 3MF and STL files
// giving the same thickness to 1e-6; and an 81,920-face sphere at every vertex.
#include <unistd.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "apps/output/stl_writer.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/closed_forms.hpp"
#include "tests/support/model_3mf_writer.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

constexpr double kRadius = 0.5;
const PdeParameters kParameters{0.3, 0.2};

/// The ball as a binary STL file in the temporary folder, removed at the end of the test.
struct BallFile {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("bemshape_analysis_ball_" + std::to_string(::getpid()) + ".stl");
  BallFile() {
    const geometry::SurfaceMesh ball = geometry::make_geodesic_sphere(
        kRadius, geometry::geodesic_frequency_for_edge(kRadius, 0.09));
    output::write_binary_stl(path.string(), ball.vertices(), ball.faces());
  }
  ~BallFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
};

double max_relative_deviation(const Eigen::VectorXd& values, double reference) {
  return ((values.array() - reference).abs() / reference).maxCoeff();
}

}  // namespace

TEST_CASE(
    "measure_thickness: the ball from a file and from arrays, h_p within 2 % of the "
    "closed form, every face in one thin region") {
  const BallFile file;
  const BallSolution ball = ball_solution(kParameters, kRadius);
  const double h_p = principal_thickness(kParameters, ball.A);
  const double h_f = paper_thickness(kParameters, inverse_thickness(kParameters, 3.0 * ball.A));
  analysis::ThicknessOptions options;
  options.solve.h0 = kParameters.h0;
  options.solve.a = kParameters.a;
  options.measure = analysis::ThicknessMeasure::principal;
  const analysis::ThicknessResult from_file = analysis::measure_thickness(file.path, options);
  CAPTURE(h_p, h_f, from_file.statistics.minimum, from_file.statistics.maximum);
  CHECK(from_file.boundary.solution.report.method == "dense-lu");
  CHECK(from_file.measure_column == "h_p");
  CHECK(from_file.thickness.size() == from_file.boundary.solver_mesh.num_faces());
  CHECK(max_relative_deviation(from_file.thickness, h_p) < 0.02);
  CHECK(std::abs(from_file.statistics.median - h_p) < 0.02 * h_p);
  CHECK(from_file.statistics.unmeasurable_area == 0.0);
  CHECK(from_file.clamped_faces == 0);
  CHECK(from_file.regions.empty());
  // Carried back to every vertex and face of the input.
  CHECK(from_file.input_features.vertex.rows() == from_file.input.mesh.num_vertices());
  CHECK(from_file.input_features.face.rows() == from_file.input.mesh.num_faces());
  const Eigen::MatrixXd& at_vertices = from_file.input_features.vertex;
  CHECK(max_relative_deviation(at_vertices.col(analysis::kColumnHp), h_p) < 0.02);
  CHECK(max_relative_deviation(at_vertices.col(analysis::kColumnHf), h_f) < 0.02);
  std::vector<std::string> stages;
  for (const auto& [stage, seconds] : from_file.times.stages())
    stages.push_back(stage);
  CHECK(stages ==
        std::vector<std::string>{"read", "refine", "assemble", "solve", "features", "regions",
                                 "map_back"});

  // The same triangles as arrays, with a check whose threshold every wall is below.
  const geometry::TriangleSoup soup = geometry::read_triangle_soup(file.path);
  const geometry::PreparedMesh arrays = analysis::prepare_triangles(soup.vertices, soup.faces);
  options.min_thickness = 2.0 * h_p;
  options.map_to_input = false;
  const analysis::ThicknessResult from_arrays = analysis::measure_thickness(arrays, options);
  CHECK(from_arrays.thickness == from_file.thickness);
  CHECK(from_arrays.boundary.solution.phi == from_file.boundary.solution.phi);
  CHECK(from_arrays.input_features.vertex.size() == 0);
  REQUIRE(from_arrays.regions.size() == 1);
  CHECK(static_cast<Eigen::Index>(from_arrays.regions[0].faces) ==
        from_arrays.boundary.solver_mesh.num_faces());
  CHECK(from_arrays.regions[0].area == Approx(from_arrays.boundary.solver_mesh.area()));
}

TEST_CASE("measure_thickness: options out of range are refused before the file is read") {
  analysis::ThicknessOptions options;
  options.solve.h0 = 0.3;
  options.min_thickness = -1.0;
  CHECK_THROWS_WITH(analysis::measure_thickness(std::string("no such file.stl"), options),
                    Catch::Contains("--min-thickness"));
  options.min_thickness.reset();
  options.solve.sharp_angle_degrees = 180.0;
  CHECK_THROWS_WITH(analysis::measure_thickness(std::string("no such file.stl"), options),
                    Catch::Contains("--sharp-angle"));
  options.solve.sharp_angle_degrees = 30.0;
  options.solve.h0 = 0.0;
  CHECK_THROWS_WITH(analysis::measure_thickness(std::string("no such file.stl"), options),
                    Catch::Contains("h0 must be a positive length"));
}

TEST_CASE("measure_thickness: a part as 3MF and as STL of the same triangles, within 1e-6") {
  // A ball of radius 50 mm (coordinates irrational, so both files round them) written once
  // by lib3mf's writer and once as binary STL. Both store float32, but lib3mf's writer
  // prints six decimals, so a coordinate below 4 in magnitude (float32 step under 5e-7)
  // comes back up to 5e-7 away from the STL's, 1e-8 of the radius; its parser also lands
  // about 5 % of the coordinates one float32 step off (docs/geometry.md). The thickness, a
  // smooth function of the surface, must then agree to 1e-6 relative on every solver face.
  // h0 and the element size are the first test's in proportion (R = 0.5, h0 = 0.3), at a
  // coarser edge (500 faces).
  constexpr double kR = 50.0;
  constexpr double kSameThickness = 1e-6;
  const geometry::SurfaceMesh ball =
      geometry::make_geodesic_sphere(kR, geometry::geodesic_frequency_for_edge(kR, 15.0));
  const auto temporary = [](const std::string& extension) {
    return std::filesystem::temp_directory_path() /
           ("bemshape_analysis_ball_" + std::to_string(::getpid()) + extension);
  };
  const std::filesystem::path stl = temporary(".stl"), threemf = temporary(".3mf");
  output::write_binary_stl(stl.string(), ball.vertices(), ball.faces());
  Model3mfWriter writer("millimeter");
  writer.add_build_item(writer.add_mesh(ball.vertices(), ball.faces()));
  writer.write(threemf);

  analysis::ThicknessOptions options;
  options.solve.h0 = 30.0;
  options.solve.max_edge = 15.0;
  options.map_to_input = false;
  const analysis::ThicknessResult from_stl = analysis::measure_thickness(stl, options);
  const analysis::ThicknessResult from_3mf = analysis::measure_thickness(threemf, options);
  std::filesystem::remove(stl);
  std::filesystem::remove(threemf);
  CHECK(from_3mf.input.report.unit == "millimeter");
  CHECK(from_3mf.input.report.format.rfind("3MF", 0) == 0);
  REQUIRE(from_3mf.thickness.size() == from_stl.thickness.size());
  const double difference =
      ((from_3mf.thickness - from_stl.thickness).array().abs() / from_stl.thickness.array())
          .maxCoeff();
  CAPTURE(difference, from_stl.thickness.size());
  CHECK(difference < kSameThickness);
  // Not trivially equal: the two files give different coordinates, by at most the six
  // decimals' rounding or a float32 step at 50 (4e-6).
  const double moved =
      (from_3mf.input.mesh.vertices() - from_stl.input.mesh.vertices()).cwiseAbs().maxCoeff();
  CAPTURE(moved);
  CHECK(moved > 0.0);
  CHECK(moved < 1e-7 * kR);
}

TEST_CASE("measure_thickness: an 81,920-face sphere, h_p and h_f within 2 % at every vertex") {
  // R = 1, h0 = 0.1 (κ·h ≈ 1.4 on its 0.028 edges), --max-edge at its longest edge: the
  // solver works on the sphere's own triangles (geometry::fine_enough), on the H-matrix path.
  // s = A·x in the ball: h_p = h0(1/(h0²A) − a) and h_f = h0(1/(3h0²A) − a) everywhere on the
  // surface, and the wall is the diameter (bench/bench_sphere_surface.cpp prints the same).
  const PdeParameters pde{0.1, 0.2};
  const BallSolution ball = ball_solution(pde, 1.0);
  const double h_p = principal_thickness(pde, ball.A);
  const double h_f = paper_thickness(pde, inverse_thickness(pde, 3.0 * ball.A));
  const geometry::SurfaceMesh sphere = geometry::make_geodesic_sphere(1.0, 64);
  REQUIRE(sphere.num_faces() == 81920);
  analysis::ThicknessOptions options;
  options.solve.h0 = pde.h0;
  options.solve.a = pde.a;
  options.solve.max_edge = sphere.max_edge_length();
  options.measure = analysis::ThicknessMeasure::principal;
  const analysis::ThicknessResult result = analysis::measure_thickness(
      analysis::prepare_triangles(sphere.vertices(), sphere.faces(), "sphere"), options);
  CHECK(result.boundary.solver_mesh.num_faces() == 81920);
  const Eigen::MatrixXd& vertex = result.input_features.vertex;
  REQUIRE(vertex.rows() == sphere.num_vertices());
  const double hp_error = ((vertex.col(analysis::kColumnHp).array() - h_p).abs() / h_p).maxCoeff();
  const double hf_error = ((vertex.col(analysis::kColumnHf).array() - h_f).abs() / h_f).maxCoeff();
  CAPTURE(h_p, h_f, hp_error, hf_error);
  CHECK(hp_error < 0.02);
  CHECK(hf_error < 0.02);
}

TEST_CASE("measure_thickness: the wall reading solves to 1e-5 unless --tolerance says otherwise, "
          "and reads the same walls as at 1e-6") {
  // A 100 × 80 × 4 plate on the H-matrix path: without a tolerance the wall reading's GMRES
  // stops at analysis::kWallReadingTolerance, with 1e-6 it goes on; the zero of s half a wall
  // deep moves by about the relative error of s, so the readings agree to 1e-5 of the wall.
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("bemshape_analysis_plate_" + std::to_string(::getpid()) + ".stl");
  const geometry::SurfaceMesh plate =
      geometry::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(100, 80, 4), 100.0);
  output::write_binary_stl(path.string(), plate.vertices(), plate.faces());
  const auto read = [&](std::optional<double> tolerance) {
    analysis::ThicknessOptions options;
    options.solve.h0 = 3.6;
    options.solve.solver.method = analysis::SolverMethod::hmatrix;
    options.solve.solver.tolerance = tolerance;
    return analysis::measure_thickness(path, options);
  };
  const analysis::ThicknessResult by_default = read(std::nullopt);
  const analysis::ThicknessResult tight = read(1e-6);
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  const auto& loose_report = by_default.boundary.solution.report;
  const auto& tight_report = tight.boundary.solution.report;
  CAPTURE(loose_report.iterations, tight_report.iterations, loose_report.preconditioned_residual,
          tight_report.preconditioned_residual);
  CHECK(loose_report.preconditioned_residual <= analysis::kWallReadingTolerance);
  CHECK(loose_report.preconditioned_residual > analysis::kSurfaceValuesTolerance);
  CHECK(tight_report.preconditioned_residual <= 1e-6);
  CHECK(loose_report.iterations < tight_report.iterations);
  const auto& a = by_default.statistics;
  const auto& b = tight.statistics;
  CAPTURE(a.median, b.median, a.p05, b.p05, a.p95, b.p95);
  CHECK(a.median == Approx(4.0).epsilon(0.01));
  for (const auto& [x, y] : {std::pair{a.median, b.median}, {a.p05, b.p05}, {a.p95, b.p95}})
    CHECK(std::abs(x - y) <= 1e-5 * 4.0);
}
