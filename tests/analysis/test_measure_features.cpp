// analysis/measure_features.hpp on the validation ball (R = 0.5, h0 = 0.3, a = 0.2): s = A·x
// and f_h = 3·h0²·A inside (tests/support/closed_forms.hpp), the inside flags, and an absurd
// grid refused before the solve.
#include <catch2/catch.hpp>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_features.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"
#include "tests/support/closed_forms.hpp"

using namespace bemshape;
using namespace bemshape::testing;

namespace {

constexpr double kRadius = 0.5;
const PdeParameters kParameters{0.3, 0.2};

geometry::PreparedMesh ball() {
  const geometry::SurfaceMesh mesh =
      geometry::make_geodesic_sphere(kRadius, geometry::geodesic_frequency_for_edge(kRadius, 0.09));
  return analysis::prepare_triangles(mesh.vertices(), mesh.faces(), "ball");
}

analysis::FeaturesOptions ball_options() {
  analysis::FeaturesOptions options;
  options.solve.h0 = kParameters.h0;
  options.solve.a = kParameters.a;
  return options;
}

}  // namespace

TEST_CASE("measure_features on the ball: f_h within 1 % and s = A·x inside, outside flagged") {
  const BallSolution closed = ball_solution(kParameters, kRadius);
  const double f_h = inverse_thickness(kParameters, 3.0 * closed.A);
  Eigen::MatrixX3d points(4, 3);
  points << 0, 0, 0, 0.1, 0.05, -0.1, -0.2, 0.1, 0.15, 0.7, 0, 0;
  const analysis::FeaturesResult r = analysis::measure_features(ball(), points, ball_options());
  REQUIRE(r.points.rows() == 4);
  CHECK_FALSE(r.grid.has_value());
  CHECK(r.parameters.skeleton_width == r.boundary.max_edge);  // the default at points
  for (Eigen::Index p = 0; p < 3; ++p) {
    CAPTURE(p, r.features.f_h(p), f_h);
    CHECK(r.field.inside[static_cast<std::size_t>(p)]);
    CHECK(std::abs(r.features.f_h(p) - f_h) < 0.01 * f_h);
    const Eigen::Vector3d s = r.field.s.row(p).transpose();
    CHECK((s - closed.A * points.row(p).transpose()).norm() < 0.01 * closed.A * kRadius);
  }
  CHECK_FALSE(r.field.inside[3]);
  CHECK(r.clamped_points == 0);
}

TEST_CASE("measure_features_on_grid: a grid of more than 10^6 nodes is refused before solving") {
  CHECK_THROWS_AS(analysis::measure_features_on_grid(ball(), 0.001, ball_options()), ResourceError);
  CHECK_THROWS_WITH(analysis::measure_features_on_grid(ball(), 0.001, ball_options()),
                    Catch::Contains("--grid 0.001 gives") && Catch::Contains("or coarser"));
  CHECK_THROWS_AS(analysis::measure_features_on_grid(ball(), -1.0, ball_options()), InputError);
  // The grid covers the bounding box symmetrically, at most a spacing to spare on each side.
  const analysis::PointGrid grid = analysis::grid_over(ball().report.bounding_box, 0.3);
  for (int d = 0; d < 3; ++d) {
    CHECK(grid.origin[d] <= -kRadius + 1e-12);
    CHECK(grid.origin[d] + 0.3 * double(grid.cells[d]) >= kRadius - 1e-12);
    CHECK(grid.origin[d] > -kRadius - 0.3);
  }
  CHECK(grid.nodes().rows() == static_cast<Eigen::Index>(grid.node_count()));
}
