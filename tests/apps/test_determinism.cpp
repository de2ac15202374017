// Determinism of the bemshape executable: the same input, options and thread count give
// bit-identical output files, and 1 and 2 threads (--threads) agree to 1e-10 relative
// (OpenMP splits the dense assembly, the LU's matrix products and the point evaluation
// differently, so the rounding of sums may differ in the last bits, but no more).
#include <stdlib.h>

#include <catch2/catch.hpp>

#include "geometry/primitive_meshes.hpp"
#include "tests/apps/bemshape_runner.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

/// Agreement of two runs: |a − b| ≤ 1e-10 · (largest |value| of the column), the scale of
/// the column (a normal component near 0 is compared at the scale of the normals, 1).
constexpr double kThreadAgreement = 1e-10;

double column_deviation(const CsvTable& a, const CsvTable& b) {
  REQUIRE(a.header == b.header);
  REQUIRE(a.rows.rows() == b.rows.rows());
  double worst = 0.0;
  for (Eigen::Index c = 0; c < a.rows.cols(); ++c) {
    const double scale = std::max(a.rows.col(c).cwiseAbs().maxCoeff(), 1e-300);
    worst = std::max(worst, (a.rows.col(c) - b.rows.col(c)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

/// A ball of 500 faces (radius 0.5): a solve of a few seconds.
std::string small_ball() {
  static const std::string path =
      write_mesh(geometry::make_geodesic_sphere(0.5, 5), "determinism_ball.stl");
  return path;
}

/// Runs `command` (a bemshape command line without --threads and -o) twice with 2 threads and
/// once with 1, each writing a CSV: the two 2-thread files must be identical and the 1-thread
/// one within kThreadAgreement of them.
void check_csv_determinism(const std::string& command, const std::string& tag) {
  const auto run = [&](int threads, const std::string& suffix) {
    const std::string csv = scratch(tag + suffix + ".csv");
    const Run r = run_bemshape(command + " --threads " + std::to_string(threads) + " --quiet -o '" +
                               csv + "'");
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    return slurp(csv);
  };
  const std::string first = run(2, "_a"), second = run(2, "_b"), single = run(1, "_c");
  CHECK(first == second);
  const double deviation = column_deviation(parse_csv(first), parse_csv(single));
  CAPTURE(deviation);
  CHECK(deviation <= kThreadAgreement);
}

}  // namespace

TEST_CASE("thickness: same input and threads give bit-identical files, 1 vs 2 threads agree to 1e-10") {
  const auto run = [](int threads, const std::string& tag) {
    const std::string csv = scratch(tag + ".csv"), vtp = scratch(tag + ".vtp");
    const Run r = run_bemshape("thickness '" + small_ball() + "' --h0 0.3 --max-edge 0.12 --threads " +
                               std::to_string(threads) + " --quiet -o '" + csv +
                               "' --solver-output '" + vtp + "'");
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    return std::pair{slurp(csv), slurp(vtp)};
  };
  const auto first = run(2, "det_a"), second = run(2, "det_b"), single = run(1, "det_c");
  CHECK(first.first == second.first);
  CHECK(first.second == second.second);
  const double deviation = column_deviation(parse_csv(first.first), parse_csv(single.first));
  CAPTURE(deviation);
  CHECK(deviation <= kThreadAgreement);
}

// The hierarchical-matrix path on a cylinder of 3310 faces (after refinement): admissible
// blocks, the coarse space and GMRES all take part. Its coarse matrix once summed the blocks
// per thread in the order a dynamic schedule gave, and two runs differed in the ninth digit.
TEST_CASE(
    "thickness --solver hmatrix: same threads give bit-identical files, 1 vs 2 threads 1e-10") {
  const std::string cylinder = std::string(BEMSHAPE_TEST_DATA_DIR) + "/meshes/cylinder.stl";
  check_csv_determinism("thickness '" + cylinder + "' --h0 2 --solver hmatrix", "hdet");
}

TEST_CASE("features --grid: same threads bit-identical, 1 vs 2 threads 1e-10") {
  check_csv_determinism("features '" + small_ball() + "' --h0 0.3 --max-edge 0.12 --grid 0.15",
                        "feat");
}

TEST_CASE("fem on a PNG: same threads give a bit-identical .vti") {
  const std::string png = write_l_shape_png("determinism_l.png");
  // fem has no --threads option: the thread count comes from OMP_NUM_THREADS.
  ::setenv("OMP_NUM_THREADS", "2", 1);
  const auto run = [&](const std::string& tag) {
    const std::string vti = scratch(tag + ".vti");
    const Run r = run_bemshape("fem '" + png + "' --cell 1 --h0 10 -o '" + vti + "'");
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    return slurp(vti);
  };
  const std::string first = run("fem_a"), second = run("fem_b");
  ::unsetenv("OMP_NUM_THREADS");
  CHECK(first.size() > 1000);
  CHECK(first == second);
}
