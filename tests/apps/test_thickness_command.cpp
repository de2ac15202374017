// `bemshape thickness` end to end, through the real executable, against the closed forms of
// docs/theory.md (tests/support/closed_forms.hpp) and against invariances. Solids are
// generated (geometry/primitive_meshes.hpp) and handed over as binary STL; each solve is kept
// at N ≲ 2000 faces so the dense path (O(N²) memory, O(N³) time) stays well under a minute
// on two cores. make_test_mesh (tests/apps) writes the same solids for reproducing a run.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include <Eigen/Geometry>

#include "core/huge_pages.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"
#include "tests/apps/output/file_readers.hpp"
#include "tests/support/closed_forms.hpp"
#include "tests/support/time_bound.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

/// The ball of the validation: R = 0.5, h0 = 0.3, a = 0.2, at the default element size
/// 1.5·a·h0 = 0.09 (1280 faces).
constexpr double kBallRadius = 0.5;
const PdeParameters kParameters{0.3, 0.2};

std::string ball_file(double max_edge, const std::string& name) {
  return write_mesh(geometry::make_geodesic_sphere(
                        kBallRadius, geometry::geodesic_frequency_for_edge(kBallRadius, max_edge)),
                    name);
}

double max_relative_deviation(const Eigen::VectorXd& values, double reference) {
  return ((values.array() - reference).abs() / reference).maxCoeff();
}

}  // namespace

TEST_CASE("ball: surface h_p and h_f within 2 % of the closed form, n_f along the normal") {
  const BallSolution ball = ball_solution(kParameters, kBallRadius);
  const double h_p = principal_thickness(kParameters, ball.A);
  const double h_f = paper_thickness(kParameters, inverse_thickness(kParameters, 3.0 * ball.A));
  const std::string mesh = ball_file(0.09, "ball.stl");
  const std::string csv = scratch("ball.csv"), json = scratch("ball.json");
  // --measure sphere: the surface value h_p under its explicit name (the default, wall, is
  // checked at the end of this test).
  const Run r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --measure sphere -o '" + csv +
                             "' --report '" + json + "' --quiet");
  CAPTURE(r.out, r.err, h_p, h_f);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());  // --quiet

  const CsvTable table = parse_csv(slurp(csv));
  CHECK(table.header_line() == "x,y,z,thickness,h_f,h_p,n_x,n_y,n_z");  // no wall search
  CHECK(table.rows.rows() == 642);                    // one row per vertex of the input
  CHECK(table.col("thickness") == table.col("h_p"));  // --measure sphere
  CHECK(max_relative_deviation(table.col("h_p"), h_p) < 0.02);
  CHECK(max_relative_deviation(table.col("h_f"), h_f) < 0.02);
  for (Eigen::Index v = 0; v < table.rows.rows(); ++v) {
    const Eigen::Vector3d x(table.rows(v, 0), table.rows(v, 1), table.rows(v, 2));
    const Eigen::Vector3d n(table.rows(v, 6), table.rows(v, 7), table.rows(v, 8));
    CHECK(n.dot(x.normalized()) > 0.999);  // s = A·x: n_f is the outward normal
  }

  const nlohmann::json report = read_json(json);
  CHECK(report["units"] == "lengths in the input file's units");
  CHECK(report["parameters"]["h0"] == 0.3);
  CHECK(report["parameters"]["measure"] == "sphere");
  CHECK(report["thickness"]["measure"] == "h_p");
  CHECK(report["parameters"]["max_edge"].get<double>() == Approx(1.5 * 0.2 * 0.3));
  CHECK(report["parameters"]["max_edge_rule"].get<std::string>().starts_with("default"));
  CHECK(report["parameters"]["march"].is_string());  // the build's instruction set
  CHECK(report["mesh"]["input_faces"] == 1280);
  CHECK(report["check"].is_null());  // no --min-thickness
  CHECK(report["solver"]["method"] == "dense-lu");
  CHECK(report["solver"]["residual"].get<double>() < 1e-10);
  for (const char* key : {"min", "max", "mean", "median", "p05", "p95"})
    CHECK(std::abs(report["thickness"][key].get<double>() / h_p - 1.0) < 0.02);
  const auto& t = report["thickness"];
  CHECK(t["min"] <= t["p05"]);
  CHECK(t["p05"] <= t["median"]);
  CHECK(t["median"] <= t["p95"]);
  CHECK(t["p95"] <= t["max"]);
  const Eigen::Vector3d min_location(t["min_location"][0], t["min_location"][1],
                                     t["min_location"][2]);
  CHECK(min_location.norm() == Approx(kBallRadius).epsilon(0.02));  // on the surface
  CHECK(report["memory"]["peak_mb"].get<double>() > 0.0);
  for (const char* stage : {"read", "refine", "assemble", "solve", "features", "total"})
    CHECK(report["timing"][stage].get<double>() >= 0.0);

  // The default, wall: a ball's wall is its diameter, read at every vertex (the mid-surface
  // search reaches the centre from every point), with h_p beside it.
  const std::string wall_csv = scratch("ball_wall.csv");
  REQUIRE(run_bemshape("thickness '" + mesh + "' --h0 0.3 -o '" + wall_csv + "' --quiet")
              .exit_code == 0);
  const CsvTable wall = parse_csv(slurp(wall_csv));
  CHECK(wall.header_line() == "x,y,z,thickness,h_f,h_p,n_x,n_y,n_z,wall");
  CHECK(wall.col("thickness") == wall.col("wall"));
  // The wall reading's graded mesh has elements as long as the ball's radius allows (a fifth
  // of --measure sphere's faces here): the surface values beside the wall come from it and
  // are coarser than --measure sphere's (within 7 % of h_p instead of 2 %).
  CHECK(max_relative_deviation(wall.col("h_p"), h_p) < 0.07);
  CHECK(max_relative_deviation(wall.col("wall"), 2.0 * kBallRadius) < 0.01);
}

TEST_CASE("ball: --measure paper writes h_f as the thickness and VTP and PLY carry the CSV's values") {
  // Coarser than the default rule (edge 0.12, 720 faces): this test checks the files, not
  // the accuracy.
  const std::string mesh = ball_file(0.12, "ball_coarse.stl");
  const std::string options = "--h0 0.3 --max-edge 0.12 --measure paper --quiet";
  const std::string csv = scratch("paper.csv"), vtp = scratch("paper.vtp"),
                    ply = scratch("paper.ply");
  for (const std::string& out : {csv, vtp, ply})
    REQUIRE(run_bemshape("thickness '" + mesh + "' " + options + " -o '" + out + "'").exit_code ==
            0);
  const CsvTable table = parse_csv(slurp(csv));
  CHECK(table.col("thickness") == table.col("h_f"));

  const VtpFile file = parse_vtp(slurp(vtp));
  REQUIRE(file.points == table.rows.rows());
  CHECK(file.polys == 720);
  CHECK(file.coordinates == table.rows.leftCols(3));
  CHECK(file.point_data.at("thickness").col(0) == table.col("thickness"));
  CHECK(file.point_data.at("h_p").col(0) == table.col("h_p"));
  CHECK(file.point_data.at("n_f").col(2) == table.col("n_z"));
  // Face values: area-weighted means of solver faces on each face, so within the range of
  // the surface's values.
  const Eigen::VectorXd faces = file.cell_data.at("thickness").col(0);
  CHECK(faces.minCoeff() >= 0.99 * table.col("thickness").minCoeff());
  CHECK(faces.maxCoeff() <= 1.01 * table.col("thickness").maxCoeff());

  const PlyFile colours = parse_ply(slurp(ply), "thickness");
  REQUIRE(colours.vertices.rows() == table.rows.rows());
  CHECK(colours.field == table.col("thickness").cast<float>());
  CHECK(colours.vertices == table.rows.leftCols(3).cast<float>());
}

TEST_CASE("shell R1 = 0.7, R2 = 1.0: h_p and h_f on both spheres within 3 % of the closed form") {
  // s = ψ(r)·x̂ with ψ = A r + B/r² in the solid: ∇s has the radial eigenvalue ψ' = A − 2B/r³
  // and the double tangential one ψ/r = A + B/r³, so div s = 3A everywhere in the solid and
  // λ_max differs between the two spheres. Frequencies 7 and 10 (2980 faces, longest edge
  // 0.13) with --max-edge 0.135, so the solver takes the input as it is: the default rule
  // (edge 0.09, ≈ 6900 faces) costs minutes of dense LU.
  const double r1 = 0.7, r2 = 1.0;
  const ShellSolution shell = shell_solution(kParameters, r1, r2);
  const auto lambda_max = [&](double r) {
    return std::max(shell.dpsi_solid(r), shell.psi(r) / r);
  };
  const double h_p_inner = principal_thickness(kParameters, lambda_max(r1));
  const double h_p_outer = principal_thickness(kParameters, lambda_max(r2));
  const double h_f = paper_thickness(kParameters, inverse_thickness(kParameters, 3.0 * shell.A));
  // The wall is 0.3 thick and curved: neither measure is 0.3, and the two spheres differ.
  CHECK(std::abs(h_p_inner - h_p_outer) > 0.05 * h_p_outer);
  const std::string mesh =
      write_mesh(geometry::make_spherical_shell(r1, r2, 7, 10), "shell.stl");
  const std::string csv = scratch("shell.csv"), json = scratch("shell.json");
  const Run r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.135 --measure sphere -o '" +
                             csv + "' --report '" + json + "' --quiet");
  CAPTURE(r.out, r.err, h_p_inner, h_p_outer, h_f);
  REQUIRE(r.exit_code == 0);
  const CsvTable table = parse_csv(slurp(csv));
  REQUIRE(table.rows.rows() == 1494);  // 10·7² + 2 and 10·10² + 2 vertices
  double inner_error = 0, outer_error = 0, h_f_error = 0;
  int inner = 0;
  for (Eigen::Index v = 0; v < table.rows.rows(); ++v) {
    const Eigen::Vector3d x(table.rows(v, 0), table.rows(v, 1), table.rows(v, 2));
    const bool on_inner = x.norm() < 0.85;
    inner += on_inner;
    const double h_p = on_inner ? h_p_inner : h_p_outer;
    double& error = on_inner ? inner_error : outer_error;
    error = std::max(error, std::abs(table.rows(v, table.column("h_p")) / h_p - 1.0));
    h_f_error = std::max(h_f_error, std::abs(table.rows(v, table.column("h_f")) / h_f - 1.0));
    // n_f = s/|s| with s = ψ x̂ and ψ > 0 across the wall: radial, outward on both spheres
    // (into the cavity's side is −x̂ on the inner sphere, so n_f is not the surface normal
    // there).
    const Eigen::Vector3d n(table.rows(v, 6), table.rows(v, 7), table.rows(v, 8));
    CHECK(std::abs(n.dot(x.normalized())) > 0.999);
  }
  CAPTURE(inner_error, outer_error, h_f_error);
  CHECK(inner == 492);
  CHECK(inner_error < 0.03);
  CHECK(outer_error < 0.03);
  CHECK(h_f_error < 0.03);

  const nlohmann::json report = read_json(json);
  CHECK(report["mesh"]["input_faces"] == 2980);
  CHECK(report["mesh"]["solver_faces"] == 2980);
  const auto& t = report["thickness"];
  CHECK(t["min"].get<double>() == Approx(std::min(h_p_inner, h_p_outer)).epsilon(0.03));
  CHECK(t["max"].get<double>() == Approx(std::max(h_p_inner, h_p_outer)).epsilon(0.03));
  // Area-weighted: the outer sphere holds 1/(1 + 0.7²) ≈ 67 % of the area, so the median is
  // the outer sphere's value.
  CHECK(t["median"].get<double>() == Approx(h_p_outer).epsilon(0.03));
}

TEST_CASE("plate 2 × 2 × 0.3: thickness in the middle within 2 % of 0.3 (CSV and JSON)") {
  // The default rule (edge 0.09) would give ≈ 3000 faces; flat walls are accurate up to
  // κ·h ≈ 5, so --max-edge 0.15 (≈ 1500 solver faces) is used. The in-plane size 2 leaves
  // 3.3·h0 between the middle and the rim, where the rim's influence has decayed.
  const std::string mesh = write_mesh(
      geometry::make_box(Eigen::Vector3d(-1, -1, -0.15), Eigen::Vector3d(1, 1, 0.15), 0.15),
      "plate.stl");
  const std::string csv = scratch("plate.csv"), json = scratch("plate.json");
  const Run r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.15 -o '" + csv +
                             "' --report '" + json + "' --quiet");
  CAPTURE(r.out, r.err);
  REQUIRE(r.exit_code == 0);
  const CsvTable table = parse_csv(slurp(csv));
  int middle = 0;
  for (Eigen::Index v = 0; v < table.rows.rows(); ++v) {
    if (std::abs(table.rows(v, 0)) > 0.5 || std::abs(table.rows(v, 1)) > 0.5)
      continue;
    ++middle;
    CHECK(table.rows(v, table.column("h_p")) == Approx(0.3).epsilon(0.02));
    CHECK(table.rows(v, table.column("h_f")) == Approx(0.3).epsilon(0.02));
    CHECK(std::abs(table.rows(v, table.column("n_z"))) > 0.999);  // across the plate
  }
  CHECK(middle > 50);
  nlohmann::json report = read_json(json);
  CHECK(report["parameters"]["max_edge_rule"] == "--max-edge");
  // The wall measure (the default) reads the plate's 0.3 up to its rims and corners.
  CHECK(report["thickness"]["measure"] == "wall");
  CHECK(report["thickness"]["min"].get<double>() == Approx(0.3).epsilon(0.02));
  CHECK(report["thickness"]["max"].get<double>() == Approx(0.3).epsilon(0.02));
  const Run wall_check = run_bemshape("thickness '" + mesh +
                                      "' --h0 0.3 --max-edge 0.15 --min-thickness 0.294 --quiet");
  CHECK(wall_check.exit_code == 0);
  // The sphere at the surface: within half the thickness of a rim no sphere of diameter 0.3
  // fits, so the surface reads thinner there (a band of ≈ 46 % of the area), while the middle
  // (|x|, |y| < 0.5 on both faces, area 2) is in no region thinner than 0.98·0.3.
  const Run check = run_bemshape("thickness '" + mesh +
                                 "' --h0 0.3 --max-edge 0.15 --measure sphere "
                                 "--min-thickness 0.294 --min-region-area 0 --report '" +
                                 json + "' --quiet");
  CHECK(check.exit_code == 1);
  report = read_json(json);
  double thin_area = 0.0;
  for (const auto& region : report["check"]["regions"])
    thin_area += region["area"].get<double>();
  CHECK(thin_area > 0.0);
  CHECK(thin_area < report["mesh"]["area"].get<double>() - 2.0);
}

TEST_CASE("rod R = 0.3, length 4: h_p and h_f at mid-length within 3 % of the infinite rod") {
  // --max-edge 0.12 (1344 faces) instead of the default 0.09 (2354 faces, several minutes of
  // dense LU on two shared cores).
  const double A = rod_slope(kParameters, 0.3);
  const double h_p = principal_thickness(kParameters, A);
  const double h_f = paper_thickness(kParameters, inverse_thickness(kParameters, 2.0 * A));
  CHECK(h_p == Approx(0.632).margin(0.0005));
  CHECK(h_f == Approx(0.286).margin(0.0005));
  const std::string mesh = write_mesh(geometry::make_cylinder(0.3, 4.0, 0.12), "rod.stl");
  const std::string csv = scratch("rod.csv");
  const Run r =
      run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.12 -o '" + csv + "' --quiet");
  CAPTURE(r.out, r.err);
  REQUIRE(r.exit_code == 0);
  const CsvTable table = parse_csv(slurp(csv));
  int middle = 0;
  for (Eigen::Index v = 0; v < table.rows.rows(); ++v) {
    if (std::abs(table.rows(v, 2)) > 0.5)
      continue;
    ++middle;
    CAPTURE(table.rows.row(v));
    CHECK(table.rows(v, table.column("h_p")) == Approx(h_p).epsilon(0.03));
    CHECK(table.rows(v, table.column("h_f")) == Approx(h_f).epsilon(0.03));
  }
  CHECK(middle > 20);
}

TEST_CASE("invariance: rotation and translation change no thickness and scaling scales them") {
  // A coarse ball (500 faces, every edge a crease the remesher keeps), so all solver meshes
  // are the same triangles moved. STL stores float32: for the 1e-6 checks the vertices are
  // put on a dyadic grid (multiples of 2^-20) and moved by maps that are exact in float32 —
  // the 120° rotation about (1, 1, 1) (a cyclic permutation of the axes), a dyadic
  // translation and the scale factor 8 — so every file holds exactly the moved geometry.
  // A general rotation is checked too, with the tolerance float32 rounding allows.
  geometry::SurfaceMesh ball = geometry::make_geodesic_sphere(kBallRadius, 5);
  const double grid = std::ldexp(1.0, -20);
  ball =
      geometry::SurfaceMesh((ball.vertices() / grid).array().round().matrix() * grid, ball.faces());
  Eigen::Matrix3d cyclic;
  cyclic << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  const Eigen::Vector3d translation(3.25, -1.5, 0.75);
  const Eigen::Matrix3d general =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const auto thickness = [](const geometry::SurfaceMesh& mesh, const std::string& options,
                            const std::string& name) {
    const std::string csv = scratch(name + ".csv");
    const Run r = run_bemshape("thickness '" + write_mesh(mesh, name + ".stl") + "' " + options +
                               " -o '" + csv + "' --quiet");
    REQUIRE(r.exit_code == 0);
    return parse_csv(slurp(csv));
  };
  const std::string options = "--h0 0.3 --max-edge 0.12";
  const CsvTable a = thickness(ball, options, "inv_base");
  const CsvTable b =
      thickness(geometry::transformed(ball, cyclic, translation), options, "inv_moved");
  const CsvTable c =
      thickness(geometry::transformed(ball, Eigen::Matrix3d::Identity(), {0, 0, 0}, 8.0),
                "--h0 2.4 --max-edge 0.96", "inv_scaled");
  const CsvTable d =
      thickness(geometry::transformed(ball, general, translation), options, "inv_general");
  REQUIRE(a.rows.rows() == b.rows.rows());
  REQUIRE(a.rows.rows() == c.rows.rows());
  REQUIRE(a.rows.rows() == d.rows.rows());
  CHECK(b.rows.leftCols(3).transpose() ==
        (cyclic * a.rows.leftCols(3).transpose()).colwise() + translation);
  for (const char* column : {"h_p", "h_f"}) {
    CAPTURE(column);
    const Eigen::VectorXd ta = a.col(column), tb = b.col(column), tc = c.col(column),
                          td = d.col(column);
    CHECK(((tb - ta).array().abs() / ta.array()).maxCoeff() < 1e-6);
    CHECK(((tc - 8.0 * ta).array().abs() / (8.0 * ta.array())).maxCoeff() < 1e-6);
    // float32 moves the vertices by up to 2e-7 (6e-8 of 3.7), 2e-6 of the 0.1 edges.
    CHECK(((td - ta).array().abs() / ta.array()).maxCoeff() < 2e-5);
  }
  // n_f turns with the part.
  for (Eigen::Index v = 0; v < a.rows.rows(); ++v) {
    const Eigen::Vector3d na(a.rows(v, 6), a.rows(v, 7), a.rows(v, 8));
    const Eigen::Vector3d nb(b.rows(v, 6), b.rows(v, 7), b.rows(v, 8));
    const Eigen::Vector3d nd(d.rows(v, 6), d.rows(v, 7), d.rows(v, 8));
    CHECK((cyclic * na - nb).norm() < 1e-6);
    CHECK((general * na - nd).norm() < 1e-4);
  }
}

TEST_CASE(
    "minimum-thickness check: a threshold above the thickest wall fails with exit 1 and one "
    "region covering the ball and one below the minimum passes") {
  const std::string mesh = ball_file(0.12, "check_ball.stl");
  const std::string json = scratch("check.json");
  // --min-thickness alone also sets h0.
  Run r = run_bemshape("thickness '" + mesh + "' --min-thickness 1.5 --h0 0.3 --max-edge 0.12 " +
                       "--report '" + json + "' --quiet");
  CAPTURE(r.out, r.err);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.out, Catch::Contains("FAIL"));
  nlohmann::json report = read_json(json);
  const double minimum = report["thickness"]["min"];
  CHECK(report["check"]["threshold"] == 1.5);
  CHECK(report["check"]["pass"] == false);
  REQUIRE(report["check"]["regions"].size() == 1);
  const auto& region = report["check"]["regions"][0];
  CHECK(region["area"].get<double>() == Approx(report["mesh"]["area"].get<double>()));
  CHECK(region["min"].get<double>() == minimum);
  for (int k = 0; k < 3; ++k)
    CHECK(std::abs(region["centroid"][k].get<double>()) < 1e-3);  // the ball's centre

  r = run_bemshape("thickness '" + mesh + "' --min-thickness " + std::to_string(0.999 * minimum) +
                   " --h0 0.3 --max-edge 0.12 --report '" + json + "' --quiet");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("PASS"));
  report = read_json(json);
  CHECK(report["check"]["pass"] == true);
  CHECK(report["check"]["regions"].empty());
}

TEST_CASE(
    "plate_holes.STL (12.7 mm plate): median 12.7 within 3 %, --min-thickness 13 fails "
    "with the big faces in its largest region, a threshold below the minimum passes") {
  // The default rule (edge 3.81 mm) gives ~25 000 solver faces, far beyond the dense path.
  // With every crease kept (--sharp-angle 1, the default) the tessellated hole walls stay as
  // needles of the plate's height: 1880 faces at --max-edge 40 but 4–5 minutes of assembly
  // (near-singular quadrature on needles). --sharp-angle 30 lets the remesher cross the hole
  // facets, and --max-edge 20 (κ·h = 15.7; flat walls do not need more) gives 1828
  // well-shaped faces: about 45 s per solve on two cores. The remesher then also chamfers some
  // rim and hole creases (320 faces off the input's planes, docs/usage.md); the checks below
  // measure the flat faces, which that leaves exact.
  const std::string plate = data + "/meshes/plate_holes.STL";
  const std::string json = scratch("plate_holes.json");
  const std::string options =
      " --h0 12.7 --max-edge 20 --sharp-angle 30 --quiet --report '" + json + "'";
  Run r = run_bemshape("thickness '" + plate + "' --min-thickness 13" + options);
  CAPTURE(r.out, r.err);
  CHECK(r.exit_code == 1);
  nlohmann::json report = read_json(json);
  CHECK(report["thickness"]["median"].get<double>() == Approx(12.7).epsilon(0.03));
  CHECK(report["check"]["pass"] == false);
  const auto& regions = report["check"]["regions"];
  REQUIRE(!regions.empty());
  const auto largest = std::max_element(regions.begin(), regions.end(), [](auto& x, auto& y) {
    return x["area"].template get<double>() < y["area"].template get<double>();
  });
  // The two big faces: the surface minus the outer side walls (2·(203.2 + 304.8)·12.7) and the
  // hole walls; the region covering both is centred between them, mid-plate.
  const double big_faces = report["mesh"]["area"].get<double>() - 2 * (203.2 + 304.8) * 12.7;
  CHECK((*largest)["area"].get<double>() > 0.8 * big_faces);
  CHECK((*largest)["centroid"][0].get<double>() == Approx(101.6).epsilon(0.05));
  CHECK((*largest)["centroid"][1].get<double>() == Approx(152.4).epsilon(0.05));
  CHECK((*largest)["centroid"][2].get<double>() == Approx(6.35).margin(1.5));
  // Sorted by severity: the first region holds the minimum.
  CHECK(regions[0]["min"].get<double>() == report["thickness"]["min"].get<double>());

  const double minimum = report["thickness"]["min"];
  r = run_bemshape("thickness '" + plate + "' --min-thickness " + std::to_string(0.999 * minimum) +
                   options);
  CHECK(r.exit_code == 0);
  report = read_json(json);
  CHECK(report["check"]["pass"] == true);
  CHECK(report["thickness"]["min"].get<double>() == minimum);  // same run, same numbers
}

TEST_CASE("thickness clamped to 0: warned and counted exactly when the minimum is 0") {
  // The cylinder of diameter 2 at --h0 4, read by the sphere at the surface: at --max-edge
  // 1.5 the elements are coarse for its curvature, and a few side faces get an inverse
  // thickness above 1/a (none at the default size 1.2 nor at 0.6). The count must be the solver faces the
  // report's minimum comes from, so the warning and clamped_faces appear exactly when the
  // minimum is 0. (The wall measure reads 1.97 there: it reads h_p at the axis, not at the
  // coarse surface.)
  const std::string cylinder = data + "/meshes/cylinder.stl";
  const auto run = [&](const std::string& options, const std::string& tag) {
    const std::string json = scratch(tag + ".json");
    const Run r =
        run_bemshape("thickness '" + cylinder + "' --h0 4 --measure sphere" + options +
                     " --report '" + json + "'");
    CAPTURE(r.out, r.err);
    REQUIRE(r.exit_code == 0);
    return std::pair{r.out, read_json(json)};
  };
  const auto [coarse_out, coarse] = run(" --max-edge 1.5", "clamp_coarse");
  CHECK(coarse["thickness"]["min"].get<double>() == 0.0);
  CHECK(coarse["thickness"]["clamped_faces"].get<long>() > 0);
  CHECK(coarse["thickness"]["clamped_faces"].get<long>() < 10);
  CHECK_THAT(coarse_out,
             Catch::Contains("warning      thickness clamped to 0 on " +
                             std::to_string(coarse["thickness"]["clamped_faces"].get<long>()) +
                             " solver face"));
  const auto [fine_out, fine] = run(" --max-edge 0.6", "clamp_fine");
  CHECK(fine["thickness"]["min"].get<double>() > 0.5);
  CHECK(fine["thickness"]["clamped_faces"].get<long>() == 0);
  CHECK_THAT(fine_out, !Catch::Contains("clamped"));
}

TEST_CASE("thickness: the H² far field below --tolerance 1e-6 is refused, naming --far-field") {
  const std::string mesh = ball_file(0.12, "nested_ball.stl");
  // The H² form's bases are in single precision, which a tighter tolerance rules out.
  const Run r = run_bemshape("thickness '" + mesh +
                             "' --h0 0.3 --max-edge 0.12 --solver hmatrix --far-field nested "
                             "--tolerance 1e-8 --quiet");
  CAPTURE(r.out, r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--far-field nested") && Catch::Contains("--tolerance"));
  const Run bad = run_bemshape("thickness '" + mesh + "' --h0 0.3 --far-field h3 --quiet");
  CHECK(bad.exit_code != 0);
  CHECK_THAT(bad.err, Catch::Contains("--far-field"));
}

TEST_CASE("solver hmatrix: the same thickness as --solver dense, GMRES reported in the JSON") {
  const std::string mesh = ball_file(0.12, "solver_ball.stl");
  const auto solve = [&](const std::string& solver) {
    const std::string csv = scratch("solver_" + solver + ".csv");
    const std::string json = scratch("solver_" + solver + ".json");
    const Run r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.12 --solver " +
                               solver + " --tolerance 1e-8 -o '" + csv + "' --report '" + json +
                               "' --quiet");
    CAPTURE(r.out, r.err);
    REQUIRE(r.exit_code == 0);
    return std::make_pair(parse_csv(slurp(csv)), read_json(json));
  };
  const auto [dense, dense_report] = solve("dense");
  const auto [fast, fast_report] = solve("hmatrix");
  CHECK(dense_report["solver"]["method"] == "dense-lu");
  CHECK(fast_report["solver"]["method"] == "hmatrix-gmres");
  CHECK(fast_report["solver"]["iterations"].get<int>() > 0);
  CHECK(fast_report["solver"]["gmres_restart"].get<int>() == 60);  // nothing short of memory
  CHECK(dense_report["solver"]["gmres_restart"].get<int>() == 0);
  CHECK(fast_report["solver"]["residual"].get<double>() <= 1e-8);
  // The tolerance bounds the preconditioned residual (GMRES preconditioned on the left); the
  // dense path reports its residual for both.
  CHECK(fast_report["solver"]["preconditioned_residual"].get<double>() <= 1e-8);
  CHECK(dense_report["solver"]["preconditioned_residual"].get<double>() ==
        dense_report["solver"]["residual"].get<double>());
  // The solve's stages add up to its wall time.
  double stages_s = 0.0;
  for (const char* stage : {"interior product", "exterior product", "preconditioner",
                            "Krylov and the rest"}) {
    CAPTURE(stage);
    const double s = fast_report["solver"]["solve_stages"][stage].get<double>();
    CHECK(s >= 0.0);
    stages_s += s;
  }
  CHECK(fast_report["solver"]["solve_stages"]["interior product"].get<double>() > 0.0);
  CHECK(stages_s == Approx(fast_report["timing"]["solve"].get<double>()).epsilon(1e-9));
  CHECK(dense_report["solver"]["solve_stages"].empty());
  CHECK(fast_report["solver"]["operator_mb"].get<double>() > 0.0);
  // The parts add up to the whole. On 1280 faces (leaves of 32) few blocks are far enough
  // apart to be worth compressing: the far field may be empty, every other part is there.
  double parts_mb = 0.0;
  for (const char* part : {"interior near field", "interior far field", "exterior near field",
                           "preconditioner"}) {
    CAPTURE(part);
    const double mb = fast_report["solver"]["operator_parts_mb"][part].get<double>();
    if (std::string(part) == "interior far field")
      CHECK(mb >= 0.0);
    else
      CHECK(mb > 0.0);
    parts_mb += mb;
  }
  CHECK(parts_mb == Approx(fast_report["solver"]["operator_mb"].get<double>()).epsilon(1e-12));
  CHECK(dense_report["solver"]["operator_parts_mb"].empty());
  for (const char* column : {"h_p", "h_f"}) {
    const Eigen::VectorXd a = dense.col(column), b = fast.col(column);
    CHECK(((a - b).array().abs() / a.array()).maxCoeff() < 1e-5);
  }
  // Below analysis::kAutoDenseFaces "auto" is the dense path.
  const Run r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-edge 0.12 --quiet --report '" +
                             scratch("solver_auto.json") + "'");
  REQUIRE(r.exit_code == 0);
  CHECK(read_json(scratch("solver_auto.json"))["solver"]["method"] == "dense-lu");
  CHECK(run_bemshape("thickness '" + mesh + "' --h0 0.3 --solver fast").exit_code == 2);
}

TEST_CASE("usage errors are one line on stderr, exit 2, before any work and no file is left") {
  const std::string mesh = ball_file(0.12, "usage_ball.stl");
  Run r = run_bemshape("thickness '" + mesh + "' --h0 0");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::StartsWith("bemshape: error: --h0"));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);

  r = run_bemshape("thickness '" + mesh + "' --h0 0.3 -o '" + scratch("out.xyz") + "'");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("unknown output format '.xyz'"));
  for (const char* ext : {".vtp", ".ply", ".csv"})
    CHECK_THAT(r.err, Catch::Contains(ext));
  CHECK(r.seconds < bemshape::test::time_bound(2.0));

  r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --measure median");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--measure"));

  // The dense matrix does not fit in 1 MB, less than the process holds before the solve, so
  // no coarser mesh fits either: one line saying so, no output file.
  const std::string out = scratch("never.vtp");
  r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --max-memory 1 -o '" + out + "' --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Catch::Contains("no coarser mesh fits") &&
                        Catch::Contains("use a larger --max-memory"));
  CHECK_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(scratch_folder()))
    CHECK_FALSE(entry.path().filename().string().starts_with(".never.vtp"));

  r = run_bemshape("thickness '" + data + "/bad/open_box.stl' --h0 1");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("open boundary edges"));
}

TEST_CASE("heap huge pages: requested at start where the kernel gives them only on request") {
  // core/huge_pages.hpp: bemshape restarts itself once with glibc.malloc.hugetlb=1 when the
  // kernel's THP mode is "madvise", and leaves a user's own setting alone.
  const std::string mode = transparent_huge_page_mode();
#if defined(__linux__) && defined(__GLIBC__) && (__GLIBC__ > 2 || __GLIBC_MINOR__ >= 35)
  const bool restarts = mode == "madvise";
#else
  const bool restarts = false;
#endif
  const std::string mesh = ball_file(0.2, "ball_pages.stl");
  const std::string json = scratch("ball_pages.json");
  const auto huge_pages_reported = [&] {
    const Run r = run_bemshape("thickness '" + mesh + "' --h0 0.3 --report '" + json + "' --quiet");
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    return read_json(json)["memory"]["heap_huge_pages"].get<bool>();
  };
  CAPTURE(mode);
  const char* before = std::getenv("GLIBC_TUNABLES");
  const std::string saved = before ? before : "";
  ::unsetenv("GLIBC_TUNABLES");
  CHECK(huge_pages_reported() == (mode == "always" || restarts));
  // The user's choice wins, and other tunables are kept through the restart.
  ::setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1);
  CHECK(huge_pages_reported() == (mode == "always"));
  ::setenv("GLIBC_TUNABLES", "glibc.malloc.mxfast=0", 1);
  CHECK(huge_pages_reported() == (mode == "always" || restarts));
  if (before) ::setenv("GLIBC_TUNABLES", saved.c_str(), 1); else ::unsetenv("GLIBC_TUNABLES");
}
