// analysis/compare_with_fem.hpp: options checked and a cell too coarse for any probe refused,
// naming a --cell that gives some, before either solve. (The comparison itself on the ball
// is tested end to end in tests/apps/test_compare_command.cpp.)
#include <catch2/catch.hpp>

#include "analysis/compare_with_fem.hpp"
#include "analysis/input_mesh.hpp"
#include "analysis/voxel_resolution.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

TEST_CASE("compare_with_fem: a cell too coarse for any probe is refused before the solves") {
  const geometry::SurfaceMesh mesh = geometry::make_geodesic_sphere(0.5, 4);
  const geometry::PreparedMesh ball = analysis::prepare_triangles(mesh.vertices(), mesh.faces());
  analysis::CompareOptions options;
  options.h0_follows_cell = true;
  options.cell = 0.4;
  const features::FeatureParameters p = analysis::comparison_parameters(options);
  CHECK(p.h0 == analysis::kDefaultH0Cells * 0.4);
  CHECK(p.skeleton_width == 0.4);
  CHECK_THROWS_WITH(analysis::compare_with_fem(ball, options),
                    Catch::Contains("no probe point") && Catch::Contains("use a smaller --cell"));
  options.cell = 0.0;
  CHECK_THROWS_WITH(analysis::comparison_parameters(options), Catch::Contains("--cell"));
  options.cell = 0.1;
  options.max_probes = 0;
  CHECK_THROWS_WITH(analysis::compare_with_fem(ball, options), Catch::Contains("--max-probes"));
}
