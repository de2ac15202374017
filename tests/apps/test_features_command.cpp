// `bemshape features` end to end: interior values on the ball against its closed form
// (s = A·x, f_h = 3·h0²·A = 0.801142 for R = 0.5, h0 = 0.3, a = 0.2), the inside flag, the
// grid output as VTI and CSV, and the refusal of absurd grids.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"
#include "tests/apps/output/file_readers.hpp"
#include "tests/support/closed_forms.hpp"
#include "tests/support/time_bound.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

const PdeParameters kParameters{0.3, 0.2};
constexpr double kRadius = 0.5;

}  // namespace

TEST_CASE("features --points on the ball: f_h within 1 % of 0.801142, s = A·x, inside flags") {
  const BallSolution ball = ball_solution(kParameters, kRadius);
  const double f_h = inverse_thickness(kParameters, 3.0 * ball.A);
  CHECK(f_h == Approx(0.801142).margin(1e-6));
  const std::string mesh = write_mesh(
      geometry::make_geodesic_sphere(kRadius, geometry::geodesic_frequency_for_edge(kRadius, 0.09)),
      "features_ball.stl");
  // Interior points from the centre to 0.4 R from the surface, and two outside.
  const std::string points = scratch("points.csv");
  {
    std::ofstream out(points);
    out << "x,y,z\n0,0,0\n0.1,0.05,-0.1\n-0.2,0.1,0.15\n0,0,0.3\n0.25,-0.05,0\n0.7,0,0\n"
           "0.4,0.4,0.1\n";
  }
  const std::string csv = scratch("features.csv");
  const std::string json = scratch("features.json");
  const Run r = run_bemshape("features '" + mesh + "' --points '" + points + "' --h0 0.3 -o '" +
                             csv + "' --report '" + json + "' --quiet");
  CAPTURE(r.out, r.err);
  REQUIRE(r.exit_code == 0);
  const CsvTable table = parse_csv(slurp(csv));
  CHECK(table.header_line() == "x,y,z,inside,s_x,s_y,s_z,f_h,h_f,h_p,n_x,n_y,n_z,skeleton");
  REQUIRE(table.rows.rows() == 7);
  for (Eigen::Index p = 0; p < 7; ++p) {
    const Eigen::Vector3d x = table.rows.row(p).head<3>();
    CAPTURE(p, x.transpose());
    const bool inside = x.norm() < kRadius;
    CHECK(table.rows(p, table.column("inside")) == (inside ? 1.0 : 0.0));
    if (inside) {
      CHECK(table.rows(p, table.column("f_h")) == Approx(f_h).epsilon(0.01));
      const Eigen::Vector3d s = table.rows.row(p).segment<3>(4);
      CHECK((s - ball.s(x)).norm() < 0.01 * ball.A * kRadius);
    } else {
      CHECK(table.rows(p, table.column("f_h")) == 0.0);  // χ = 0 outside
      CHECK(table.rows(p, table.column("h_p")) == 0.0);
    }
  }
  // The JSON report: the points counted by the geometry, h_f = h0(1/f_h − a) of the closed
  // form over the inside points.
  const nlohmann::json report = read_json(json);
  CHECK(report["command"] == "features");
  CHECK(report["output"] == csv);
  CHECK(report["parameters"]["h0"] == 0.3);
  CHECK(report["parameters"]["kappa"].get<double>() == Approx(2.0 / (0.2 * 0.3)));
  CHECK(report["points"]["count"] == 7);
  CHECK(report["points"]["inside"] == 5);
  CHECK(report["points"]["grid"].is_null());
  const double h_f = kParameters.h0 * (1.0 / f_h - kParameters.a);
  CHECK(report["features"]["h_f"]["min"].get<double>() == Approx(h_f).epsilon(0.02));
  CHECK(report["features"]["h_f"]["max"].get<double>() == Approx(h_f).epsilon(0.02));
  CHECK(report["timing"]["solve"].get<double>() >= 0.0);
  // Without -o the table goes to stdout.
  const Run to_stdout =
      run_bemshape("features '" + mesh + "' --points '" + points + "' --h0 0.3 --quiet");
  REQUIRE(to_stdout.exit_code == 0);
  CHECK(parse_csv(to_stdout.out).rows == table.rows);
  CHECK_THAT(r.out + to_stdout.err, !Catch::Contains("clamped"));  // f_h ≈ 0.8 < 1/a = 5
}

TEST_CASE("features: points where h_f or h_p is clamped to 0 are counted in a warning") {
  // The cylinder of diameter 2 at --h0 40, forty times its radius: near the side wall the
  // inverse thickness exceeds 1/a = 5 and the thickness h0(1/f − a) is clamped to 0. The
  // warning's count must be the inside rows of the output with h_f or h_p at 0, on stdout's
  // summary with -o, on stderr when the table goes to stdout.
  const std::string cylinder = std::string(BEMSHAPE_TEST_DATA_DIR) + "/meshes/cylinder.stl";
  const std::string points = scratch("clamp_points.csv");
  {
    std::ofstream out(points);
    out << "x,y,z\n";
    for (const double r : {0.0, 0.5, 0.9, 0.97, 0.99})
      for (int k = 0; k < 4; ++k)
        out << r * std::cos(k * std::numbers::pi / 2) << ','
            << r * std::sin(k * std::numbers::pi / 2) << ",0.5\n";
  }
  const std::string csv = scratch("clamp.csv");
  const std::string command = "features '" + cylinder + "' --points '" + points + "' --h0 40";
  const Run r = run_bemshape(command + " -o '" + csv + "' --quiet");
  CAPTURE(r.out, r.err);
  REQUIRE(r.exit_code == 0);
  const CsvTable table = parse_csv(slurp(csv));
  long clamped = 0;
  for (Eigen::Index p = 0; p < table.rows.rows(); ++p)
    if (table.rows(p, table.column("inside")) == 1.0 &&
        (table.rows(p, table.column("h_f")) == 0.0 || table.rows(p, table.column("h_p")) == 0.0))
      ++clamped;
  CHECK(clamped > 0);
  CHECK(clamped < table.rows.rows());  // the axis is far enough from the wall
  const std::string warning =
      "warning      h_f or h_p clamped to 0 at " + std::to_string(clamped) + " inside point";
  CHECK_THAT(r.out, Catch::Contains(warning));
  const Run to_stdout = run_bemshape(command + " --quiet");
  REQUIRE(to_stdout.exit_code == 0);
  CHECK_THAT(to_stdout.err, Catch::Contains(warning));
  CHECK(parse_csv(to_stdout.out).rows == table.rows);
}

TEST_CASE("features --grid: VTI over the bounding box, the same values as the CSV") {
  // Coarse ball (500 faces) and grid (spacing 0.125: 10³ nodes) — this checks the grid and
  // the files; the accuracy is the --points test's.
  const std::string mesh = write_mesh(geometry::make_geodesic_sphere(kRadius, 5), "grid_ball.stl");
  const std::string vti = scratch("grid.vti"), csv = scratch("grid.csv");
  const std::string options = " --h0 0.3 --max-edge 0.14 --grid 0.125 --quiet -o '";
  Run r = run_bemshape("features '" + mesh + "'" + options + vti + "'");
  CAPTURE(r.out, r.err);
  REQUIRE(r.exit_code == 0);
  r = run_bemshape("features '" + mesh + "'" + options + csv + "'");
  REQUIRE(r.exit_code == 0);
  const VtiFile grid = parse_vti(slurp(vti));
  const CsvTable table = parse_csv(slurp(csv));
  // Nodes symmetric about the box centre, covering the box: ceil(1/0.125) + 1 = 9 cells.
  CHECK(grid.extent == std::array<long long, 6>{0, 9, 0, 9, 0, 9});
  CHECK(grid.spacing == Eigen::Vector3d::Constant(0.125));
  REQUIRE(table.rows.rows() == 1000);
  const Eigen::Index inside = table.column("inside");
  int inside_count = 0;
  for (Eigen::Index p = 0; p < 1000; ++p) {
    // Point order x fastest, as in VTK.
    const Eigen::Vector3d node(grid.origin.x() + 0.125 * double(p % 10),
                               grid.origin.y() + 0.125 * double((p / 10) % 10),
                               grid.origin.z() + 0.125 * double(p / 100));
    CHECK((table.rows.row(p).head<3>().transpose() - node).norm() < 1e-12);
    const double r_node = node.norm();
    if (std::abs(r_node - kRadius) > 0.02)  // clear of the polyhedral surface
      CHECK(table.rows(p, inside) == (r_node < kRadius ? 1.0 : 0.0));
    inside_count += table.rows(p, inside) > 0.5;
    CHECK(grid.point_data.at("inside")(p, 0) == static_cast<float>(table.rows(p, inside)));
    CHECK(grid.point_data.at("f_h")(p, 0) == static_cast<float>(table.rows(p, 7)));
    CHECK(grid.point_data.at("h_p")(p, 0) == static_cast<float>(table.rows(p, 9)));
    for (int k = 0; k < 3; ++k) {
      CHECK(grid.point_data.at("s")(p, k) == static_cast<float>(table.rows(p, 4 + k)));
      CHECK(grid.point_data.at("n_f")(p, k) == static_cast<float>(table.rows(p, 10 + k)));
    }
  }
  CHECK(inside_count > 200);  // (4/3)π·0.5³ / 0.125³ ≈ 268
}

TEST_CASE("features: an absurd grid is refused before solving, naming a spacing that fits") {
  const std::string mesh = write_mesh(geometry::make_geodesic_sphere(kRadius, 3), "refuse.stl");
  const Run r = run_bemshape("features '" + mesh + "' --h0 0.3 --grid 0.001 --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--grid 0.001 gives"));
  CHECK_THAT(r.err, Catch::Contains("use --grid 0.01"));  // 1001³ points → 10× coarser
  CHECK(r.seconds < bemshape::test::time_bound(2.0));
  const Run both = run_bemshape("features '" + mesh + "' --h0 0.3 --grid 0.1 --points x.csv");
  CHECK(both.exit_code == 2);
  CHECK_THAT(both.err, Catch::Contains("exactly one of --points"));
  const Run vti_points = run_bemshape("features '" + mesh + "' --h0 0.3 --points x.csv -o a.vti");
  CHECK(vti_points.exit_code == 2);
}
