// `bemshape compare` end to end on the ball R = 0.5, h0 = 0.3, a = 0.2 (κ = 33.3), whose
// closed form (tests/support/closed_forms.hpp) bounds what the two methods may disagree by:
// the BEM is within 0.5 % of f_h = 0.801142 on the 1280-face ball (docs/validation.md), the
// voxel FEM within about 2.5 % at κ·cell = 2/3 and converging with the cell, so the median
// FEM–BEM difference must be a few per cent and shrink with the cell. The report's probe
// count is checked against the volume of the probe region, a ball of radius R − 2·cell.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <numeric>

#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"
#include "tests/support/closed_forms.hpp"
#include "tests/support/time_bound.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

const PdeParameters kParameters{0.3, 0.2};
constexpr double kRadius = 0.5;

std::string ball_file(double max_edge, const std::string& name) {
  return write_mesh(geometry::make_geodesic_sphere(
                        kRadius, geometry::geodesic_frequency_for_edge(kRadius, max_edge)),
                    name);
}

/// Runs compare and returns the JSON report (exit code 0 required).
nlohmann::json compare(const std::string& mesh, const std::string& options,
                       const std::string& name) {
  const std::string json = scratch(name);
  const Run r = run_bemshape("compare '" + mesh + "' --h0 0.3 " + options + " --report '" + json +
                             "' --quiet");
  CAPTURE(r.out, r.err, r.seconds);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::Contains("h_p difference, probes per bin:"));
  return read_json(json);
}

}  // namespace

TEST_CASE("compare on the ball: report keys, probe count, median differences within 3 %") {
  const double cell = 0.02;  // κ·cell = 2/3
  const nlohmann::json report =
      compare(ball_file(0.09, "compare_ball.stl"), "--cell 0.02 --max-probes 1000", "ball.json");
  CHECK(report.at("command") == "compare");
  CHECK(report.at("parameters").at("h0") == 0.3);
  CHECK(report.at("parameters").at("kappa").get<double>() == Approx(kParameters.kappa()));
  CHECK(report.at("parameters").at("cell") == cell);
  CHECK(report.at("mesh").at("solver_faces") == 1280);
  for (const auto& key : {"cells", "cg_iterations", "solid_cells"})
    CHECK(report.at("grid").contains(key));
  CHECK(report.at("timing").at("total").get<double>() > 0.0);

  // Candidates: cell centres in the ball of radius R − 2·cell (the inscribed polyhedron is
  // 1 % smaller in volume at this frequency, the centres' lattice adds ±1 %).
  const double probe_region = 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius - 2 * cell, 3);
  CHECK(report.at("probes").at("candidates").get<double>() ==
        Approx(probe_region / std::pow(cell, 3)).epsilon(0.03));
  CHECK(report.at("probes").at("count") == 1000);
  CHECK(report.at("probes").at("outside_bem") == 0);

  const nlohmann::json& difference = report.at("difference");
  for (const auto& feature : {"f_h", "h_p"}) {
    CAPTURE(feature, difference.dump(2));
    const nlohmann::json& d = difference.at(feature);
    const double median = d.at("median"), p95 = d.at("p95"), max = d.at("max");
    CHECK(0.0 <= median);
    CHECK(median <= p95);
    CHECK(p95 <= max);
    CHECK(d.at("probes") == 1000);  // nothing saturates inside a ball of thickness ~ 3·h0
    // FEM error at κ·cell = 2/3 (≤ 2.5 %) plus the BEM's (≤ 0.5 %); h_p = h0(1/(h0²λ) − a)
    // changes by 1/(1 − a·h0²λ) ≈ 1.06 times the relative change of λ.
    CHECK(median <= 0.03);
  }
  // The histogram of the h_p differences accounts for every probe and covers the maximum.
  const nlohmann::json& histogram = report.at("histogram").at("h_p");
  const std::vector<long long> counts = histogram.at("counts");
  const std::vector<double> edges = histogram.at("edges");
  CHECK(std::accumulate(counts.begin(), counts.end(), 0LL) == 1000);
  REQUIRE(edges.size() == counts.size() + 1);
  CHECK(edges.front() == 0.0);
  CHECK(edges.back() >= difference.at("h_p").at("max").get<double>());
}

TEST_CASE("compare on the ball: the median difference shrinks with the cell") {
  // A coarse BEM (500 faces, f_h within about 0.6 %) keeps this fast; the FEM's errors at
  // κ·cell = 4/3 and 1 (about 6 % and 4 %) dominate it.
  const std::string mesh = ball_file(0.14, "compare_ball500.stl");
  const std::string options = "--max-edge 0.14 --max-probes 500 --cell ";
  const nlohmann::json coarse = compare(mesh, options + "0.04", "coarse.json");
  const nlohmann::json fine = compare(mesh, options + "0.03", "fine.json");
  for (const auto& feature : {"f_h", "h_p"}) {
    const double coarse_median = coarse.at("difference").at(feature).at("median");
    const double fine_median = fine.at("difference").at(feature).at("median");
    CAPTURE(feature, coarse_median, fine_median);
    CHECK(fine_median < coarse_median);
    CHECK(fine_median < 0.06);
  }
}

TEST_CASE("compare: a cell too coarse for any probe is refused before solving") {
  const std::string mesh = ball_file(0.14, "compare_coarse_cell.stl");
  const Run r = run_bemshape("compare '" + mesh + "' --h0 0.3 --cell 0.3 --quiet");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("no probe point"));
  CHECK_THAT(r.err, Catch::Contains("use a smaller --cell"));
  CHECK(r.seconds < bemshape::test::time_bound(5.0));  // no BEM solve
  const Run no_cell = run_bemshape("compare '" + mesh + "' --h0 0.3");
  CHECK(no_cell.exit_code == 2);
  const Run bad_cell = run_bemshape("compare '" + mesh + "' --h0 0.3 --cell -1 --quiet");
  CHECK(bad_cell.exit_code == 2);
  CHECK_THAT(bad_cell.err, Catch::Contains("--cell must be a positive length"));
}
